// A table of a command: the rows of a CSV file it writes and, the same
// object, the ccma.Table Python's result holds. Each table is defined once,
// by the function that builds it (documents/*_table.h); WriteCsv writes any
// of them, python/src/tables.cc hands any of them to Python.
#ifndef CCMA_DOCUMENTS_TABLE_H_
#define CCMA_DOCUMENTS_TABLE_H_

#include <cstddef>
#include <deque>
#include <ostream>
#include <string>
#include <vector>

namespace ccma::documents {

// How a column's cells are written and typed (Python: float64, bool, int64, str).
enum class ColumnKind {
  kNumber,  // a double; an empty cell where not finite
  kFlag,    // 1 or 0
  kCount,   // an integer (exact up to 2^53)
  kText,    // text without separators (WriteCsv replaces , " and line breaks by ;)
};

struct Column {
  std::string name;  // the CSV header's name, with its unit ("x_m", "torn")
  ColumnKind kind = ColumnKind::kNumber;
  std::vector<double> values;       // every kind but kText
  std::vector<std::string> texts;   // kText
  std::size_t size() const { return kind == ColumnKind::kText ? texts.size() : values.size(); }
};

struct Table {
  std::deque<Column> columns;  // (a deque: a column added keeps the references to the others valid)
  // Appends an empty column and returns it.
  Column& Add(std::string name, ColumnKind kind = ColumnKind::kNumber);
  std::size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
};

// A text cell as the CSV holds it: , " and line breaks replaced by ;.
std::string CsvSafeText(std::string text);

// The header line, then one line per row; numbers with `digits` significant
// digits. Throws std::logic_error when the columns differ in length.
void WriteCsv(const Table& table, std::ostream& csv, int digits = 17);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_TABLE_H_
