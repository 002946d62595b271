#include "viewer/csv_reader.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/model_loader.h"
#include "viewer/view_frames.h"

namespace ccma::viewer {

// The lines of a file read in blocks, or of a text in memory: one line at a
// time, each at most kMaxCsvLineBytes, the whole at most max_bytes.
class LineSource {
 public:
  LineSource(int fd, const std::string* text, std::string path, std::size_t max_bytes)
      : fd_(fd), text_(text), path_(std::move(path)), max_bytes_(max_bytes) {
    if (fd_ >= 0) block_.resize(std::size_t{1} << 20);
  }
  ~LineSource() {
    if (fd_ >= 0) ::close(fd_);
  }
  LineSource(const LineSource&) = delete;
  LineSource& operator=(const LineSource&) = delete;

  // The next line (without its '\n') and its number (from 1); false at the end.
  bool Next(std::string* line, int* number) {
    line->clear();
    bool any = false;
    for (;;) {
      if (begin_ == end_ && !Fill()) {
        if (!any) return false;
        break;
      }
      any = true;
      const char* from = Data() + begin_;
      const void* newline = std::memchr(from, '\n', end_ - begin_);
      const std::size_t take = newline ? static_cast<const char*>(newline) - from : end_ - begin_;
      if (line->size() + take > kMaxCsvLineBytes) {
        throw ViewInputError(path_ + ":" + std::to_string(number_ + 1) + ": a line longer than " +
                             FormatMiB(kMaxCsvLineBytes) + " (the limit for a line of a CSV file)");
      }
      line->append(from, take);
      begin_ += take;
      if (newline) {
        ++begin_;
        break;
      }
    }
    *number = ++number_;
    return true;
  }

  // Back to the first line.
  void Rewind() {
    number_ = 0;
    begin_ = end_ = 0;
    consumed_ = 0;
    if (fd_ >= 0 && ::lseek(fd_, 0, SEEK_SET) != 0) {
      throw ViewInputError(path_ + ": cannot read the CSV file again (" + std::strerror(errno) + ")");
    }
  }

 private:
  const char* Data() const { return fd_ >= 0 ? block_.data() : text_->data(); }

  // More bytes into [begin_, end_); false at the end of the file.
  bool Fill() {
    if (fd_ < 0) {
      if (consumed_ != 0) return false;
      consumed_ = text_->size();
      begin_ = 0;
      end_ = consumed_;
      return end_ > 0;
    }
    for (;;) {
      const ssize_t got = ::read(fd_, block_.data(), block_.size());
      if (got < 0 && errno == EINTR) continue;
      if (got < 0) throw ViewInputError(path_ + ": cannot read the CSV file (" + std::strerror(errno) + ")");
      consumed_ += static_cast<std::size_t>(got);
      if (consumed_ > max_bytes_) {  // it grew, or st_size was not its size
        throw ViewInputError(path_ + ": larger than " + FormatMiB(max_bytes_) + " (the limit for a CSV file)");
      }
      begin_ = 0;
      end_ = static_cast<std::size_t>(got);
      return got > 0;
    }
  }

  int fd_;
  const std::string* text_;
  std::string path_;
  std::size_t max_bytes_;
  std::vector<char> block_;
  std::size_t begin_ = 0, end_ = 0, consumed_ = 0;
  int number_ = 0;
};

namespace {

// Cells of a line: one more than its commas.
std::size_t CountCells(const std::string& line) {
  return static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
}

std::string LineWhere(const std::string& path, int line) { return path + ":" + std::to_string(line); }

// A line that holds a row or the header: not empty, not a '#' comment
// (a trailing '\r' removed first).
bool IsContent(std::string* line) {
  if (!line->empty() && line->back() == '\r') line->pop_back();
  return !line->empty() && (*line)[0] != '#';
}

// Whether [b, e) is a plain decimal number, all of it: an optional sign,
// digits with at most one point (at least one digit), an optional exponent
// e/E, sign, digits. strtod alone also reads hexadecimal ("0x1p3"), "inf",
// "nan" and leading spaces, none of which ccma writes. On success `order`
// is the power of ten of its first non-zero digit (exponent included,
// clamped to +-1e8), or INT_MIN for zero.
bool IsDecimal(const char* b, const char* e, long* order) {
  const auto digit = [&](const char* p) { return p < e && *p >= '0' && *p <= '9'; };
  const char* p = b;
  if (p < e && (*p == '+' || *p == '-')) ++p;
  long digits = 0, lead = 0;
  bool nonzero = false;
  for (; digit(p); ++p, ++digits) {
    if (!nonzero && *p != '0') nonzero = true, lead = 0;
    if (nonzero) ++lead;  // digits from the first non-zero one to the point
  }
  long first = lead - 1;  // power of ten of the first non-zero digit
  if (p < e && *p == '.') {
    long place = 0;
    for (++p; digit(p); ++p, ++digits) {
      --place;
      if (!nonzero && *p != '0') nonzero = true, first = place;
    }
  }
  if (digits == 0) return false;
  long exponent = 0;
  if (p < e && (*p == 'e' || *p == 'E')) {
    ++p;
    const bool negative = p < e && *p == '-';
    if (p < e && (*p == '+' || *p == '-')) ++p;
    if (!digit(p)) return false;
    for (; digit(p); ++p) exponent = std::min(100000000L, exponent * 10 + (*p - '0'));
    if (negative) exponent = -exponent;
  }
  *order = nonzero ? first + exponent : std::numeric_limits<long>::min();
  return p == e;
}

}  // namespace

CsvReader::CsvReader(const std::string& path, const CsvLimits& limits, const std::vector<std::string>& columns)
    : path_(path), limits_(limits) {
  std::string error;
  const int fd = internal::OpenRegularFile(path, limits.max_bytes, "CSV file", &error);
  if (fd < 0) throw ViewInputError(error);
  source_ = std::make_unique<LineSource>(fd, nullptr, path, limits.max_bytes);
  ReadHeader(columns);
}

CsvReader::CsvReader(const std::string* text, const std::string& source, const CsvLimits& limits,
                     const std::vector<std::string>& columns)
    : path_(source), limits_(limits) {
  if (text->size() > limits.max_bytes) {
    throw ViewInputError(source + ": " + std::to_string(text->size()) + " bytes, more than the " +
                         std::to_string(limits.max_bytes) + " a CSV file may have");
  }
  source_ = std::make_unique<LineSource>(-1, text, source, limits.max_bytes);
  ReadHeader(columns);
}

CsvReader::~CsvReader() = default;

void CsvReader::ReadHeader(const std::vector<std::string>& columns) {
  while (source_->Next(&line_text_, &line_)) {
    if (!IsContent(&line_text_)) continue;
    // Counted before anything is split: a line of commas would otherwise
    // become one string per cell (tens of bytes each, for one byte of input).
    const std::size_t count = CountCells(line_text_);
    if (count > kMaxCsvColumns) {
      throw ViewInputError(LineWhere(path_, line_) + ": " + std::to_string(count) + " cells, more than the " +
                           std::to_string(kMaxCsvColumns) + " columns a table may have");
    }
    std::size_t from = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t comma = std::min(line_text_.find(',', from), line_text_.size());
      header_.push_back(line_text_.substr(from, comma - from));
      from = comma + 1;
    }
    slot_.assign(count, -1);
    for (std::size_t i = 0; i < count; ++i) is_text_.push_back(limits_.text_columns.count(header_[i]) > 0);
    for (const std::string& name : columns) {
      if (std::find(names_.begin(), names_.end(), name) != names_.end()) continue;
      // The last column of that name, as a name -> column map would give.
      const auto it = std::find(header_.rbegin(), header_.rend(), name);
      if (it == header_.rend()) continue;
      slot_[static_cast<std::size_t>(header_.rend() - it - 1)] = static_cast<int>(names_.size());
      names_.push_back(name);
    }
    cells_.assign(names_.size(), std::nan(""));
    return;
  }
  throw ViewInputError(path_ + ": no header line");
}

int CsvReader::Find(const std::string& name, bool required) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  if (it != names_.end()) return static_cast<int>(it - names_.begin());
  if (required) throw ViewInputError(path_ + ": no column '" + Printable(name) + "' in the header");
  return -1;
}

std::string CsvReader::Where(int index) const {
  return LineWhere(path_, line_) + ": column '" + Printable(names_[static_cast<std::size_t>(index)]) + "'";
}

long CsvReader::CountRows() {
  long rows = 0;
  const int header_line = line_;
  while (source_->Next(&line_text_, &line_)) {
    if (!IsContent(&line_text_)) continue;
    CheckShape(line_text_, rows);
    ++rows;
  }
  source_->Rewind();
  // Back past the header (the lines up to it, read again).
  int number = 0;
  while (number < header_line && source_->Next(&line_text_, &number)) {
  }
  line_ = header_line;
  return rows;
}

// A row's cell count (as the header's) and its index (below max_rows),
// checked before anything is split.
void CsvReader::CheckShape(const std::string& line, long index) const {
  const std::size_t count = CountCells(line);
  if (count > kMaxCsvColumns) {
    throw ViewInputError(LineWhere(path_, line_) + ": " + std::to_string(count) + " cells, more than the " +
                         std::to_string(kMaxCsvColumns) + " columns a table may have");
  }
  if (count != header_.size()) {
    throw ViewInputError(LineWhere(path_, line_) + ": " + std::to_string(count) + " cells, the header has " +
                         std::to_string(header_.size()));
  }
  if (index >= limits_.max_rows) {
    throw ViewInputError(LineWhere(path_, line_) + ": more than " + std::to_string(limits_.max_rows) + " rows");
  }
}

bool CsvReader::Next() {
  while (source_->Next(&line_text_, &line_)) {
    if (!IsContent(&line_text_)) continue;
    CheckShape(line_text_, row_ + 1);
    ++row_;
    CheckCells(line_text_);
    return true;
  }
  if (row_ < 0) throw ViewInputError(path_ + ": no rows");
  return false;
}

// Every cell of the row: a number within bounds (the ones asked for into
// cells_), empty, or in a text column. A cell whose first digit lies below
// 1e6 passes on its syntax alone; the others, and every cell asked for, are
// read by strtod.
void CsvReader::CheckCells(const std::string& line) {
  std::size_t from = 0;
  for (std::size_t i = 0; i < header_.size(); ++i) {
    const std::size_t comma = std::min(line.find(',', from), line.size());
    const char* b = line.data() + from;
    const char* e = line.data() + comma;
    from = comma + 1;
    const int slot = slot_[i];
    if (is_text_[i]) {
      if (slot >= 0) cells_[static_cast<std::size_t>(slot)] = std::nan("");
      continue;
    }
    long order = 0;
    const bool decimal = IsDecimal(b, e, &order);
    if (b == e) {
      if (slot >= 0) cells_[static_cast<std::size_t>(slot)] = std::nan("");  // e.g. a failed step's value
      continue;
    }
    if (slot < 0 && decimal && order < 6) continue;
    cell_.assign(b, e);
    const auto where = [&] { return LineWhere(path_, line_) + ": column '" + Printable(header_[i]) + "'"; };
    char* end = nullptr;
    const double v = std::strtod(cell_.c_str(), &end);
    // strtod reads "nan", "inf" and overflows to inf: numbers to it, never to
    // a scene. Its ERANGE is not checked: it flags underflow too, and a
    // subnormal such as 4.9e-324 (what ccma writes for the smallest double)
    // is a number.
    if (end != cell_.c_str() && *end == '\0' && !std::isfinite(v)) {
      throw ViewInputError(where() + ": not a finite number: " + Quote(cell_));
    }
    if (!decimal) throw ViewInputError(where() + ": not a number: " + Quote(cell_));
    if (std::abs(v) > kMaxMagnitude * 100) throw ViewInputError(where() + ": " + Quote(cell_) + " is outside [-1e6, 1e6]");
    if (slot >= 0) cells_[static_cast<std::size_t>(slot)] = v;
  }
}

}  // namespace ccma::viewer
