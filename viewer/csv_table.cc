#include "viewer/csv_table.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/model_loader.h"
#include "viewer/view_frames.h"

namespace ccma::viewer {
namespace {

std::vector<std::string> SplitCommas(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// Cells of a line: one more than its commas.
std::size_t CountCells(const std::string& line) {
  return static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
}

std::string LineWhere(const std::string& path, int line) { return path + ":" + std::to_string(line); }

// Whether `text` is a plain decimal number, all of it: an optional sign,
// digits with at most one point (at least one digit), an optional exponent
// e/E, sign, digits. strtod alone also reads hexadecimal ("0x1p3"), "inf",
// "nan" and leading spaces, none of which ccma writes.
bool IsDecimal(const std::string& text) {
  const auto digit = [&](std::size_t i) { return i < text.size() && text[i] >= '0' && text[i] <= '9'; };
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t digits = 0;
  for (; digit(i); ++i) ++digits;
  if (i < text.size() && text[i] == '.') {
    for (++i; digit(i); ++i) ++digits;
  }
  if (digits == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (!digit(i)) return false;
    while (digit(i)) ++i;
  }
  return i == text.size();
}

double ParseNumber(const CsvTable& t, int line, const std::string& text, int col) {
  const std::string where = LineWhere(t.path, line) + ": column '" + Printable(t.header[col]) + "'";
  if (text.empty()) return std::nan("");  // an empty cell (e.g. a failed step's value)
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  // strtod reads "nan", "inf" and overflows to inf: numbers to it, never to a
  // scene. Its ERANGE is not checked: it flags underflow too, and a subnormal
  // such as 4.9e-324 (what ccma writes for the smallest double) is a number.
  if (end != text.c_str() && *end == '\0' && !std::isfinite(v)) {
    throw ViewInputError(where + ": not a finite number: " + Quote(text));
  }
  if (!IsDecimal(text)) throw ViewInputError(where + ": not a number: " + Quote(text));
  if (std::abs(v) > kMaxMagnitude * 100) throw ViewInputError(where + ": " + Quote(text) + " is outside [-1e6, 1e6]");
  return v;
}

}  // namespace

int CsvTable::Find(const std::string& name, bool required) const {
  const auto it = column.find(name);
  if (it != column.end()) return it->second;
  if (required) throw ViewInputError(path + ": no column '" + Printable(name) + "' in the header");
  return -1;
}

std::string CsvTable::Where(std::size_t row, int col) const {
  return LineWhere(path, lines[row]) + ": column '" + Printable(header[col]) + "'";
}

CsvTable ReadCsvTable(const std::string& path, const CsvLimits& limits) {
  std::string text, error;
  if (!internal::ReadRegularFile(path, limits.max_bytes, "CSV file", &text, &error)) throw ViewInputError(error);
  return ParseCsvTable(text, path, limits);
}

CsvTable ParseCsvTable(const std::string& text, const std::string& path, const CsvLimits& limits) {
  if (text.size() > limits.max_bytes) {
    throw ViewInputError(path + ": " + std::to_string(text.size()) + " bytes, more than the " +
                         std::to_string(limits.max_bytes) + " a CSV file may have");
  }
  CsvTable t;
  t.path = path;
  std::vector<bool> is_text;
  // Lines cut from the text in place (no second copy of a large file).
  std::string line;
  int number = 0;
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find('\n', start), text.size());
    line.assign(text, start, end - start);
    start = end + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    // Counted before anything is split: a line of commas would otherwise
    // become one string per cell (tens of bytes each, for one byte of input).
    const std::size_t count = CountCells(line);
    if (count > kMaxCsvColumns) {
      throw ViewInputError(LineWhere(path, number) + ": " + std::to_string(count) + " cells, more than the " +
                           std::to_string(kMaxCsvColumns) + " columns a table may have");
    }
    if (!t.header.empty() && count != t.header.size()) {
      throw ViewInputError(LineWhere(path, number) + ": " + std::to_string(count) + " cells, the header has " +
                           std::to_string(t.header.size()));
    }
    const std::vector<std::string> cells = SplitCommas(line);
    if (t.header.empty()) {
      t.header = cells;
      for (size_t i = 0; i < cells.size(); ++i) {
        t.column[cells[i]] = static_cast<int>(i);
        is_text.push_back(limits.text_columns.count(cells[i]) > 0);
      }
      continue;
    }
    if (cells.size() != t.header.size()) {
      throw ViewInputError(LineWhere(path, number) + ": " + std::to_string(cells.size()) + " cells, the header has " +
                           std::to_string(t.header.size()));
    }
    if (static_cast<long>(t.rows.size()) >= limits.max_rows) {
      throw ViewInputError(LineWhere(path, number) + ": more than " + std::to_string(limits.max_rows) + " rows");
    }
    std::vector<double> row(cells.size());
    for (size_t i = 0; i < cells.size(); ++i) {
      row[i] = is_text[i] ? std::nan("") : ParseNumber(t, number, cells[i], static_cast<int>(i));
    }
    t.rows.push_back(std::move(row));
    t.lines.push_back(number);
  }
  if (t.header.empty()) throw ViewInputError(path + ": no header line");
  if (t.rows.empty()) throw ViewInputError(path + ": no rows");
  return t;
}

}  // namespace ccma::viewer
