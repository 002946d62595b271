// A CSV as ccma's commands write them ('#' comment lines, one header, rows
// of numbers), read from an untrusted file for `ccma view`: the trajectory,
// replay and workspace files all go through here, so that they are bounded
// and their messages name the file, line and column the same way.
#ifndef CCMA_VIEWER_CSV_TABLE_H_
#define CCMA_VIEWER_CSV_TABLE_H_

#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace ccma::viewer {

// Columns a table may have. With it a table's memory grows with its file
// alone (at most one cell per byte, 8 bytes each, and ~50 bytes per row) and,
// while a line is split, at most this many cell strings exist.
constexpr std::size_t kMaxCsvColumns = 100000;

// What a file may be: at most `max_bytes` [bytes] and `max_rows` rows;
// `text_columns` are not parsed (e.g. a workspace map's `limited_by`).
struct CsvLimits {
  std::size_t max_bytes = 0;
  long max_rows = 0;
  std::set<std::string> text_columns;
};

struct CsvTable {
  std::string path;
  std::vector<std::string> header;
  std::map<std::string, int> column;
  // One entry per cell: a finite number within [-1e6, 1e6], or NaN for an
  // empty cell (e.g. a failed step's value) and for every text column.
  std::vector<std::vector<double>> rows;
  std::vector<int> lines;  // file line (1-based) of each row

  // Index of a column, or -1 (optional) / throws ViewInputError (required).
  int Find(const std::string& name, bool required) const;
  // "path:line: column 'name'", the start of a message about one cell.
  std::string Where(std::size_t row, int col) const;
};

// Reads and checks the whole file. Throws ViewInputError (view_frames.h)
// when it is not a regular file within max_bytes, has no header or no rows,
// a line with more than kMaxCsvColumns cells,
// a row with another number of cells than the header, more than max_rows
// rows, or a cell that is neither empty nor a plain decimal number within
// [-1e6, 1e6] (outside a text column: an optional sign, digits with at most
// one point, an optional exponent; subnormals such as 4.9e-324 are numbers,
// hexadecimal "0x1p3", "inf", "nan" and spaces are not); the message names
// file, line and column.
CsvTable ReadCsvTable(const std::string& path, const CsvLimits& limits);

// The same for the text of a file already in memory; `source` names it in
// messages and becomes the table's path. Text over limits.max_bytes is
// refused as the file would be.
CsvTable ParseCsvTable(const std::string& text, const std::string& source, const CsvLimits& limits);

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_CSV_TABLE_H_
