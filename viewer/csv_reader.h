// A CSV as ccma's commands write them ('#' comment lines, one header, rows
// of numbers), read row by row from an untrusted file for `ccma view`: the
// trajectory, replay and workspace files all go through here, so that they
// are bounded and their messages name the file, line and column the same way.
//
// Memory does not grow with the file: the reader holds one block of the file
// (1 MiB) and one line, and of a row's cells it keeps only those of the
// columns it was asked for; every cell is still checked. A caller keeps what
// it needs of each row (a workspace map's points; a trajectory's frames,
// thinned evenly, CountRows() first).
#ifndef CCMA_VIEWER_CSV_READER_H_
#define CCMA_VIEWER_CSV_READER_H_

#include <cstddef>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace ccma::viewer {

// Columns a table may have: while a line is split, at most this many cells
// are looked at, counted before anything is split.
constexpr std::size_t kMaxCsvColumns = 100000;
// The longest line [bytes]: 100,000 cells of 160 characters. A longer one is
// refused (naming its line) before it is held in memory.
constexpr std::size_t kMaxCsvLineBytes = std::size_t{16} << 20;

// What a file may be: at most `max_bytes` [bytes] and `max_rows` rows;
// `text_columns` are not parsed (e.g. a workspace map's `limited_by`).
struct CsvLimits {
  std::size_t max_bytes = 0;
  long max_rows = 0;
  std::set<std::string> text_columns;
};

class LineSource;

// Rows of one file (or text), one at a time. Every call may throw
// ViewInputError (view_frames.h) when the file is not a regular file within
// max_bytes, has no header or no rows, a line longer than kMaxCsvLineBytes
// or with more than kMaxCsvColumns cells, a row with another number of
// cells than the header, more than max_rows rows, or a cell that is neither
// empty nor a plain decimal number within [-1e6, 1e6] (outside a text
// column: an optional sign, digits with at most one point, an optional
// exponent; subnormals such as 4.9e-324 are numbers, hexadecimal "0x1p3",
// "inf", "nan" and spaces are not); the message names file, line and column.
class CsvReader {
 public:
  // Opens `path` and reads its header. `columns`: the names whose cells
  // Cell() returns (other cells are checked, then dropped).
  CsvReader(const std::string& path, const CsvLimits& limits, const std::vector<std::string>& columns);
  // The same over text already in memory (not copied: it must outlive the
  // reader); `source` names it in messages. Text over limits.max_bytes is
  // refused as the file would be.
  CsvReader(const std::string* text, const std::string& source, const CsvLimits& limits,
            const std::vector<std::string>& columns);
  ~CsvReader();
  CsvReader(const CsvReader&) = delete;
  CsvReader& operator=(const CsvReader&) = delete;

  const std::string& path() const { return path_; }
  // Index for Cell() of a column asked for that the header has; -1 when the
  // header lacks it (optional) or throws ViewInputError (required).
  int Find(const std::string& name, bool required) const;

  // The rows of the file, counted by reading it through once (each row's
  // cell count checked, its cells not yet), the reader then back before its
  // first row. Call it before the first Next().
  long CountRows();
  // Reads the next row and checks all its cells: false at the end of the
  // file (throws "no rows" when it had none).
  bool Next();
  // The current row's cell of Find()'s column `index`: a number, or NaN for
  // an empty cell (e.g. a failed step's value) and in a text column.
  double Cell(int index) const { return cells_[static_cast<std::size_t>(index)]; }
  // The current row: its index (from 0) and its file line (from 1).
  long row() const { return row_; }
  int line() const { return line_; }
  // "path:line: column 'name'": the start of a message about a current cell.
  std::string Where(int index) const;

 private:
  void ReadHeader(const std::vector<std::string>& columns);
  void CheckShape(const std::string& line, long index) const;
  void CheckCells(const std::string& line);

  std::string path_;
  CsvLimits limits_;
  std::unique_ptr<LineSource> source_;
  std::vector<std::string> header_;
  std::vector<int> slot_;       // per header column: its index in cells_, or -1 (not asked for)
  std::vector<char> is_text_;   // per header column
  std::vector<std::string> names_;  // per index of cells_: its column's name (asked for, in the header)
  std::vector<double> cells_;
  std::string line_text_, cell_;
  long row_ = -1;
  int line_ = 0;
};

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_CSV_READER_H_
