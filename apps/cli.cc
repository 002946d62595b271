#include "apps/cli.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <gflags/gflags.h>

#include "ccma/internal/format.h"

namespace ccma::cli {
namespace {

bool IsIntegerType(const std::string& gflags_type) {
  return gflags_type == "int32" || gflags_type == "int64" || gflags_type == "uint32" || gflags_type == "uint64";
}

// An optional sign and decimal digits, nothing else: gflags would read
// "0x10" as 16 (and strtol skips leading spaces).
bool PlainDecimal(const std::string& value) {
  const std::size_t digits = value[0] == '+' || value[0] == '-' ? 1 : 0;
  return value.size() > digits && value.find_first_not_of("0123456789", digits) == std::string::npos;
}

}  // namespace

void ParseFlags(const std::vector<std::string>& args, const std::set<std::string>& allowed,
                const std::string& command) {
  std::set<std::string> seen;
  for (const std::string& arg : args) {
    if (arg.rfind("--", 0) != 0 || arg.size() == 2) {
      throw UsageError("ccma " + command + ": unexpected argument " + Quote(arg) + " (flags are --name=value)");
    }
    const size_t eq = arg.find('=');
    const std::string name = arg.substr(2, eq == std::string::npos ? std::string::npos : eq - 2);
    if (allowed.count(name) == 0) {
      std::string known;
      for (const std::string& a : allowed) known += " --" + a;
      throw UsageError("ccma " + command + ": unknown flag " + Quote("--" + name) + " (known:" + known + ")");
    }
    if (!seen.insert(name).second) {
      throw UsageError("ccma " + command + ": flag '--" + name + "' given twice");
    }
    gflags::CommandLineFlagInfo info;
    const bool is_bool = gflags::GetCommandLineFlagInfo(name.c_str(), &info) && info.type == "bool";
    if (eq == std::string::npos && !is_bool) {
      throw UsageError("ccma " + command + ": flag '--" + name + "' needs a value (--" + name +
                       "=...)");
    }
    const std::string value = eq == std::string::npos ? "true" : arg.substr(eq + 1);
    if (value.empty()) {
      throw UsageError("ccma " + command + ": flag '--" + name + "' has an empty value");
    }
    // SetCommandLineOption validates the value's type and returns "" on error
    // (unlike ParseCommandLineFlags, it never exits the process).
    if (IsIntegerType(info.type) && !PlainDecimal(value)) {
      throw UsageError("ccma " + command + ": bad value " + Quote(value) + " for --" + name +
                       " (a decimal integer: digits, no hex, no spaces)");
    }
    if (gflags::SetCommandLineOption(name.c_str(), value.c_str()).empty()) {
      throw UsageError("ccma " + command + ": bad value " + Quote(value) + " for --" + name);
    }
  }
}

Eigen::VectorXd ParseNumberList(const std::string& text, const std::string& flag) {
  std::vector<double> values;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const char* begin = item.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &end);
    while (end != nullptr && *end == ' ') ++end;
    // Decimal only (strtod also reads hex floats); underflow to a subnormal is a number.
    const bool decimal = item.find_first_not_of("0123456789+-.eE ") == std::string::npos;
    if (item.empty() || end == begin || *end != '\0' || !decimal || !std::isfinite(v)) {
      throw UsageError("--" + flag + ": " + Quote(item) + " is not a finite number");
    }
    values.push_back(v);
  }
  if (!text.empty() && text.back() == ',') {
    throw UsageError("--" + flag + ": trailing comma");
  }
  if (values.empty()) throw UsageError("--" + flag + ": no numbers given");
  return Eigen::Map<Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

namespace {

std::string ShellWord(const std::string& word) {
  const std::string plain = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_@%+=:,./-";
  if (!word.empty() && word.find_first_not_of(plain) == std::string::npos) return word;
  bool printable = true;
  for (const char c : word) printable = printable && static_cast<unsigned char>(c) >= 0x20 && c != 0x7f;
  std::string out;
  if (printable) {  // '...' keeps everything; a ' inside is closed, escaped and reopened
    for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return "'" + out + "'";
  }
  for (const char c : word) {
    const unsigned char b = static_cast<unsigned char>(c);
    char escaped[8];
    std::snprintf(escaped, sizeof escaped, "\\x%02x", b);
    out += b >= 0x20 && b < 0x7f && c != '\\' && c != '\'' ? std::string(1, c) : std::string(escaped);
  }
  return "$'" + out + "'";
}

}  // namespace

std::string CommandLineForShell() {
  std::string line;
  for (const std::string& word : gflags::GetArgvs()) line += (line.empty() ? "" : " ") + ShellWord(word);
  return line;
}

std::string RequireFlag(const std::string& value, const std::string& flag,
                        const std::string& command) {
  if (value.empty()) throw UsageError("ccma " + command + ": --" + flag + " is required");
  return value;
}

}  // namespace ccma::cli
