#include "documents/retime_document.h"

#include <cstdio>
#include <stdexcept>

#include "ccma/internal/format.h"

namespace ccma::documents {
namespace {

nlohmann::json InfeasibleJson(const RetimeInfeasible& why) {
  nlohmann::json j = {{"row", why.row}, {"line", why.line}, {"time_s", why.time}, {"kind", why.kind}};
  if (why.kind == "not assembled") return j;
  j["control"] = why.control;
  j["effort"] = why.effort;
  j["limit"] = why.kind == "push" ? nlohmann::json(why.upper) : nlohmann::json::array({why.lower, why.upper});
  return j;
}

std::string InfeasibleWarning(const RetimeInfeasible& why) {
  const std::string at = "row " + std::to_string(why.row) + " (line " + std::to_string(why.line) + ", time_s " +
                         FormatG(why.time) + ")";
  if (why.kind == "not assembled") return "the path does not assemble at " + at + ": not retimed";
  const std::string limit = why.kind == "push" ? "push_limit " + FormatG(why.upper)
                                               : "[" + FormatG(why.lower) + ", " + FormatG(why.upper) + "]";
  return "infeasible at rest: " + why.control + "'s " + why.kind + " " + FormatG(why.effort) + " at " + at +
         " is beyond its " + limit + " even standing still: not retimed";
}

}  // namespace

Document RetimeDocument(const RetimeReport& report, size_t rows) {
  Document d;
  nlohmann::json& j = d.json;
  j["feasible"] = report.feasible;
  j["rows"] = rows;
  j["original_duration_s"] = report.original_duration;
  if (!report.feasible) {
    if (report.infeasible) {
      j["infeasible"] = InfeasibleJson(*report.infeasible);
      d.Warn(InfeasibleWarning(*report.infeasible));
    }
    return d;
  }
  j["duration_s"] = report.duration;
  if (report.uniform_duration > 0) j["uniform_duration_s"] = report.uniform_duration;
  j["method"] = report.method;
  j["verified_scale"] = report.verified_scale;
  j["limiting"] = nlohmann::json::array();
  for (const RetimeLimitShare& l : report.limiting) {
    j["limiting"].push_back({{"name", l.name}, {"kind", l.kind}, {"share", l.share}});
  }
  return d;
}

std::string RetimedCsv(const std::string& input, const std::vector<int>& lines, const std::vector<double>& times) {
  if (lines.size() != times.size()) throw std::invalid_argument("RetimedCsv: lines and times differ in size");
  std::vector<std::string> text;  // the input's lines, without their '\n'
  for (size_t b = 0; b <= input.size();) {
    const size_t e = input.find('\n', b);
    text.push_back(input.substr(b, e == std::string::npos ? std::string::npos : e - b));
    if (e == std::string::npos) break;
    b = e + 1;
  }
  // The header: the first line that is neither empty nor a '#' comment.
  int column = -1;
  for (const std::string& line : text) {
    if (line.empty() || line[0] == '#' || line == "\r") continue;
    size_t b = 0;
    for (int i = 0;; ++i) {
      size_t e = line.find(',', b);
      std::string name = line.substr(b, e == std::string::npos ? std::string::npos : e - b);
      if (!name.empty() && name.back() == '\r') name.pop_back();
      if (name == "time_s") column = i;
      if (e == std::string::npos || column >= 0) break;
      b = e + 1;
    }
    break;
  }
  if (column < 0) throw std::invalid_argument("RetimedCsv: no time_s column");
  for (size_t r = 0; r < lines.size(); ++r) {
    if (lines[r] < 1 || static_cast<size_t>(lines[r]) > text.size()) throw std::invalid_argument("RetimedCsv: no line");
    std::string& line = text[static_cast<size_t>(lines[r] - 1)];
    size_t b = 0;
    for (int i = 0; i < column; ++i) {
      b = line.find(',', b);
      if (b == std::string::npos) throw std::invalid_argument("RetimedCsv: a row without a time_s cell");
      ++b;
    }
    size_t e = line.find(',', b);
    if (e == std::string::npos) e = line.back() == '\r' ? line.size() - 1 : line.size();
    char cell[32];
    std::snprintf(cell, sizeof cell, "%.17g", times[r]);
    line.replace(b, e - b, cell);
  }
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) out += text[i] + (i + 1 < text.size() ? "\n" : "");
  return out;
}

}  // namespace ccma::documents
