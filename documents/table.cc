#include "documents/table.h"

#include <cmath>
#include <iomanip>
#include <stdexcept>
#include <utility>

namespace ccma::documents {

Column& Table::Add(std::string name, ColumnKind kind) {
  columns.push_back(Column{std::move(name), kind, {}, {}});
  return columns.back();
}

std::string CsvSafeText(std::string text) {
  for (char& ch : text) {
    if (ch == ',' || ch == '"' || ch == '\n' || ch == '\r') ch = ';';
  }
  return text;
}

namespace {

void WriteCell(const Column& c, std::size_t row, std::ostream& csv) {
  switch (c.kind) {
    case ColumnKind::kNumber:
      if (std::isfinite(c.values[row])) csv << c.values[row];
      return;
    case ColumnKind::kFlag:
      csv << (c.values[row] != 0 ? 1 : 0);
      return;
    case ColumnKind::kCount:
      csv << static_cast<long long>(c.values[row]);
      return;
    case ColumnKind::kText:
      csv << CsvSafeText(c.texts[row]);
      return;
  }
}

}  // namespace

void WriteCsv(const Table& table, std::ostream& csv, int digits) {
  const std::size_t rows = table.rows();
  for (const Column& c : table.columns) {
    if (c.size() != rows) throw std::logic_error("table column '" + c.name + "' has another length");
  }
  for (std::size_t k = 0; k < table.columns.size(); ++k) csv << (k ? "," : "") << table.columns[k].name;
  csv << "\n";
  const std::streamsize old = csv.precision(digits);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t k = 0; k < table.columns.size(); ++k) {
      if (k) csv << ",";
      WriteCell(table.columns[k], r, csv);
    }
    csv << "\n";
  }
  csv.precision(old);
}

}  // namespace ccma::documents
