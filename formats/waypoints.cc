#include "formats/waypoints.h"

#include "ccma/internal/format.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "ccma/limits.h"
#include "formats/model_loader.h"

namespace ccma {
namespace {

std::string FormatBoundG(double x) { return FormatG(x, 15); }  // 10000, 1000000

constexpr const char* kHeader = "time,x,y,z,roll,pitch,yaw";
constexpr int kColumns = 7;

// The columns of a waypoint and the bound of each, shared by the file's
// parser and WaypointListError so that a file and a list obey one rule.
struct Column {
  const char* name;
  double max;
  const char* unit;
};
constexpr Column kColumnRules[kColumns] = {{"time", kMaxTime, "s"},      {"x", kMaxMagnitude, "m"},
                                           {"y", kMaxMagnitude, "m"},    {"z", kMaxMagnitude, "m"},
                                           {"roll", kMaxMagnitude, "rad"}, {"pitch", kMaxMagnitude, "rad"},
                                           {"yaw", kMaxMagnitude, "rad"}};

// False for NaN and infinities too.
bool WithinBound(double v, const Column& column) { return std::abs(v) <= column.max; }

// Times may repeat (a leg done in no time) but never decrease.
bool GoesBackwards(const Waypoint& w, const Waypoint& previous) { return w.time < previous.time; }

double ValueOf(const Waypoint& w, int column) {
  return column == 0 ? w.time : column <= 3 ? w.position[column - 1] : w.rpy[column - 4];
}

// Parses one row of the file, in memory, line by line.
class WaypointParser {
 public:
  explicit WaypointParser(const std::string& path) : path_(path) {}

  std::vector<Waypoint> Parse(const std::string& text) {
    std::size_t start = 0;
    while (start < text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      ++line_;
      ParseLine(text.substr(start, end - start));
      start = end + 1;
    }
    if (!header_) throw WaypointError(path_ + ": no header line (" + kHeader + ")");
    if (waypoints_.empty()) throw WaypointError(path_ + ": no waypoints");
    return std::move(waypoints_);
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    throw WaypointError(path_ + ":" + std::to_string(line_) + ": " + what);
  }

  void ParseLine(std::string line) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') return;
    if (!header_) {
      std::string compact;
      for (const char c : line) {
        if (c != ' ' && c != '\t') compact += c;
      }
      if (compact != kHeader) Fail(std::string("the header must be ") + kHeader);
      header_ = true;
      return;
    }
    if (waypoints_.size() >= static_cast<std::size_t>(kMaxWaypoints)) {
      Fail("more than " + std::to_string(kMaxWaypoints) + " waypoints");
    }
    const std::vector<double> values = Values(line);
    Waypoint w;
    w.time = values[0];
    w.position = Eigen::Vector3d(values[1], values[2], values[3]);
    w.rpy = Eigen::Vector3d(values[4], values[5], values[6]);
    if (!waypoints_.empty() && GoesBackwards(w, waypoints_.back())) Fail("time goes backwards");
    waypoints_.push_back(w);
  }

  // The 7 numbers of a row, each checked against its range.
  std::vector<double> Values(const std::string& line) const {
    std::vector<double> values;
    std::size_t start = 0;
    for (;;) {
      std::size_t end = line.find(',', start);
      if (end == std::string::npos) end = line.size();
      if (values.size() == static_cast<std::size_t>(kColumns)) {
        Fail("expected " + std::to_string(kColumns) + " values, got more");
      }
      const std::string item = line.substr(start, end - start);
      const int column = static_cast<int>(values.size());
      values.push_back(Number(item, kColumnRules[column]));
      if (end == line.size()) break;
      start = end + 1;
    }
    if (values.size() != static_cast<std::size_t>(kColumns)) {
      Fail("expected " + std::to_string(kColumns) + " values, got " +
           std::to_string(values.size()));
    }
    return values;
  }

  double Number(const std::string& item, const Column& column) const {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(item.c_str(), &end);
    const char* const last = item.c_str() + item.size();  // an embedded NUL is not the end
    while (end != last && (*end == ' ' || *end == '\t')) ++end;
    // Decimal only: strtod would also read hex floats, inf and nan. Underflow
    // (a subnormal such as 4.9e-324) is a number; overflow gives inf.
    const bool decimal = item.find_first_not_of("0123456789+-.eE \t") == std::string::npos;
    if (end == item.c_str() || end != last || !decimal || !std::isfinite(v)) {
      Fail(Quote(item) + " is not a finite number (" + column.name + ")");
    }
    if (!WithinBound(v, column)) {
      Fail(Quote(item) + " must lie in [" + FormatBoundG(-column.max) + ", " + FormatBoundG(column.max) + "] (" +
           column.name + ", " + column.unit + ")");
    }
    return v;
  }

  const std::string path_;
  int line_ = 0;
  bool header_ = false;
  std::vector<Waypoint> waypoints_;
};

}  // namespace

std::vector<Waypoint> LoadWaypoints(const std::string& path) {
  std::string text;
  std::string error;
  if (!internal::ReadRegularFile(path, kMaxWaypointFileBytes, "waypoint file", &text, &error)) {
    throw WaypointError(error);
  }
  return ParseWaypoints(text, path);
}

std::vector<Waypoint> ParseWaypoints(const std::string& text, const std::string& source) {
  if (text.size() > kMaxWaypointFileBytes) {
    throw WaypointError(source + ": " + std::to_string(text.size()) + " bytes, more than the " +
                        std::to_string(kMaxWaypointFileBytes) + " a waypoint file may have");
  }
  return WaypointParser(source).Parse(text);
}

std::string WaypointListError(const std::vector<Waypoint>& waypoints) {
  if (waypoints.size() > static_cast<std::size_t>(kMaxWaypoints)) {
    return "waypoints: " + std::to_string(waypoints.size()) + " of them; at most " + std::to_string(kMaxWaypoints) +
           " are allowed";
  }
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const std::string name = "waypoints[" + std::to_string(i) + "]";
    for (int c = 0; c < kColumns; ++c) {
      const Column& column = kColumnRules[c];
      const double v = ValueOf(waypoints[i], c);
      if (!WithinBound(v, column)) {
        return name + "." + column.name + " (" + FormatG(v) + ") must be a finite number in [" + FormatG(-column.max) +
               ", " + FormatG(column.max) + "] (" + column.unit + ")";
      }
    }
    if (i > 0 && GoesBackwards(waypoints[i], waypoints[i - 1])) {
      return name + ".time (" + FormatG(waypoints[i].time) + ") is smaller than waypoints[" + std::to_string(i - 1) +
             "].time (" + FormatG(waypoints[i - 1].time) + "): time goes backwards";
    }
  }
  return "";
}

}  // namespace ccma
