#include "viewer/stl.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace ccma::viewer {
namespace {

constexpr std::size_t kHeaderBytes = 84;     // 80-byte header, uint32 count
constexpr std::size_t kTriangleBytes = 50;   // normal, 3 vertices (float32 x 12), uint16

std::uint32_t ReadU32(const std::string& b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 3])) << 24;
}

float ReadFloat(const std::string& b, std::size_t at) {
  const std::uint32_t bits = ReadU32(b, at);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

void WriteU32(std::uint32_t v, std::string* out) {
  for (int k = 0; k < 4; ++k) out->push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

void WriteFloat(float f, std::string* out) {
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  WriteU32(bits, out);
}

bool IsBinary(const std::string& bytes) {
  if (bytes.size() < kHeaderBytes) return false;
  const std::uint64_t count = ReadU32(bytes, 80);
  return bytes.size() == kHeaderBytes + kTriangleBytes * count;
}

std::vector<StlTriangle> ReadBinary(const std::string& bytes) {
  const std::uint64_t count = ReadU32(bytes, 80);
  // The claimed count is trusted only as far as the bytes go (IsBinary checks
  // the same; kept here so that this function is safe on its own): a header
  // claiming 1e9 triangles in a short file allocates nothing.
  if (bytes.size() < kHeaderBytes || (bytes.size() - kHeaderBytes) / kTriangleBytes < count) {
    throw StlError("binary STL: the header claims " + std::to_string(count) + " triangles, the file holds " +
                   std::to_string(bytes.size() < kHeaderBytes ? 0 : (bytes.size() - kHeaderBytes) / kTriangleBytes));
  }
  std::vector<StlTriangle> triangles(count);
  for (std::size_t t = 0; t < count; ++t) {
    const std::size_t at = kHeaderBytes + kTriangleBytes * t + 12;  // past the normal, which is recomputed
    for (int v = 0; v < 3; ++v) {
      for (int k = 0; k < 3; ++k) {
        const float x = ReadFloat(bytes, at + 12 * v + 4 * k);
        if (!std::isfinite(x)) {
          throw StlError("binary STL: triangle " + std::to_string(t + 1) + " has a vertex that is not a finite number");
        }
        triangles[t][v][k] = x;
      }
    }
  }
  return triangles;
}

// Whitespace-separated words of an ASCII STL, with their line numbers.
class AsciiWords {
 public:
  explicit AsciiWords(const std::string& text) : text_(text) {}

  bool AtEnd() {
    SkipSpace();
    return pos_ >= text_.size();
  }
  std::string Next() {
    SkipSpace();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !IsSpace(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  void SkipLine() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  }
  void Expect(const char* word) {
    const std::string got = Next();
    if (got != word) Fail(std::string("expected '") + word + "', got " + Shown(got));
  }
  float Number() {
    const std::string word = Next();
    char* end = nullptr;
    const double value = word.empty() ? NAN : std::strtod(word.c_str(), &end);
    if (word.empty() || end != word.c_str() + word.size() || !std::isfinite(value) ||
        !std::isfinite(static_cast<float>(value))) {
      Fail("expected a finite number, got " + Shown(word));
    }
    return static_cast<float>(value);
  }
  // A word for a message: quoted, clipped to 40 characters; the end of the file when empty.
  static std::string Shown(const std::string& word) {
    if (word.empty()) return "the end of the file";
    std::string shown = word.size() > 40 ? word.substr(0, 40) + "..." : word;
    for (char& c : shown) {
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    }
    return "'" + shown + "'";
  }
  [[noreturn]] void Fail(const std::string& what) const {
    throw StlError("ASCII STL, line " + std::to_string(line_) + ": " + what);
  }

 private:
  static bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
  void SkipSpace() {
    while (pos_ < text_.size() && IsSpace(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  const std::string& text_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

std::vector<StlTriangle> ReadAscii(const std::string& text) {
  AsciiWords words(text);
  std::vector<StlTriangle> triangles;
  do {
    words.Expect("solid");
    words.SkipLine();  // the solid's name
    for (std::string word = words.Next(); word != "endsolid"; word = words.Next()) {
      if (word != "facet") words.Fail("expected 'facet' or 'endsolid', got " + AsciiWords::Shown(word));
      words.Expect("normal");
      for (int k = 0; k < 3; ++k) words.Number();  // recomputed from the vertices
      words.Expect("outer");
      words.Expect("loop");
      StlTriangle t;
      for (auto& vertex : t) {
        words.Expect("vertex");
        for (float& x : vertex) x = words.Number();
      }
      words.Expect("endloop");
      words.Expect("endfacet");
      triangles.push_back(t);
    }
    words.SkipLine();  // the name after endsolid
  } while (!words.AtEnd());
  return triangles;
}

}  // namespace

std::vector<StlTriangle> ReadStl(const std::string& bytes) {
  std::vector<StlTriangle> triangles;
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  if (IsBinary(bytes)) {
    triangles = ReadBinary(bytes);
  } else if (first != std::string::npos && bytes.compare(first, 5, "solid") == 0) {
    triangles = ReadAscii(bytes);
  } else {
    throw StlError("neither a binary STL (84 bytes, then 50 per triangle, the count at byte 80) nor an ASCII STL "
                   "(starting with 'solid')");
  }
  if (triangles.empty()) throw StlError("no triangles");
  return triangles;
}

std::string WriteBinaryStl(const std::vector<StlTriangle>& triangles) {
  std::string out = "binary STL written by ccma view";
  out.resize(80, ' ');
  out.reserve(kHeaderBytes + kTriangleBytes * triangles.size());
  WriteU32(static_cast<std::uint32_t>(triangles.size()), &out);
  for (const StlTriangle& t : triangles) {
    double e1[3], e2[3];
    for (int k = 0; k < 3; ++k) {
      e1[k] = double(t[1][k]) - t[0][k];
      e2[k] = double(t[2][k]) - t[0][k];
    }
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& c : n) c = norm > 0 && std::isfinite(norm) ? c / norm : 0.0;
    for (double c : n) WriteFloat(static_cast<float>(c), &out);
    for (const auto& vertex : t) {
      for (float x : vertex) WriteFloat(x, &out);
    }
    out.append(2, '\0');
  }
  return out;
}

std::string Base64(const std::string& bytes) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t chunk = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) chunk |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) chunk |= static_cast<unsigned char>(bytes[i + 2]);
    out.push_back(kAlphabet[(chunk >> 18) & 63]);
    out.push_back(kAlphabet[(chunk >> 12) & 63]);
    out.push_back(i + 1 < bytes.size() ? kAlphabet[(chunk >> 6) & 63] : '=');
    out.push_back(i + 2 < bytes.size() ? kAlphabet[chunk & 63] : '=');
  }
  return out;
}

}  // namespace ccma::viewer
