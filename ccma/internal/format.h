// Numbers in messages: %g, so that 1e-20 reads 1e-20 and not 0.000000.
#ifndef CCMA_INTERNAL_FORMAT_H_
#define CCMA_INTERNAL_FORMAT_H_

#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <string>
#include <utility>

namespace ccma {

// Characters of untrusted text quoted back in a message.
constexpr std::size_t kQuotedChars = 40;

// Untrusted text made safe to print on one line: bytes outside printable
// ASCII (and the backslash) escaped as \xNN, cut after kQuotedChars.
inline std::string Printable(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kQuotedChars; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out += static_cast<char>(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      out += escaped;
    }
  }
  if (text.size() > kQuotedChars) out += "...";
  return out;
}

// Text for one line of a script, a table or a message: control characters
// (and DEL) replaced by '?', nothing cut (names already bounded by the model).
inline std::string OneLine(const std::string& text) {
  std::string out = text;
  for (char& c : out) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) c = '?';
  }
  return out;
}

// 'text' for a message (Printable), with the length when it was cut.
inline std::string Quote(const std::string& text) {
  std::string out = "'" + Printable(text) + "'";
  if (text.size() > kQuotedChars) out += " (" + std::to_string(text.size()) + " bytes)";
  return out;
}

// `value` with printf's %.<digits>g.
// A size in whole MiB, for messages about size limits.
// `text` with its first word renamed when it is one of `renames`' (from, to)
// pairs: a message about an option in the words its command uses.
inline std::string RenameLeadingWord(std::string text,
                                     std::initializer_list<std::pair<const char*, const char*>> renames) {
  for (const auto& [from, to] : renames) {
    const std::string word = from;
    if (text.compare(0, word.size(), word) == 0 && (text.size() == word.size() || text[word.size()] == ' ')) {
      return to + text.substr(word.size());
    }
  }
  return text;
}

inline std::string FormatMiB(std::size_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

// `value` with `digits` digits after the point (tables of results).
inline std::string FormatFixed(double value, int digits) {
  char buffer[400];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}

inline std::string FormatG(double value, int digits = 6) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

// The shortest %g text (15, 16 or 17 significant digits) that reads back to
// exactly `value`: files and messages say 0.6, not 0.59999999999999998,
// and still round-trip. 0 for both zeros.
inline std::string FormatExact(double value) {
  if (value == 0.0) return "0";
  for (int digits = 15; digits < 17; ++digits) {
    const std::string text = FormatG(value, digits);
    if (std::strtod(text.c_str(), nullptr) == value) return text;
  }
  return FormatG(value, 17);
}

}  // namespace ccma

#endif  // CCMA_INTERNAL_FORMAT_H_
