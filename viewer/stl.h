// STL meshes for the viewer: reads a binary or ASCII STL into triangles and
// writes them back as one canonical binary STL (what the page's three.js
// STLLoader is given), so that the page only ever sees what was checked here.
#ifndef CCMA_VIEWER_STL_H_
#define CCMA_VIEWER_STL_H_

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace ccma::viewer {

// A malformed STL; the message says what and, for ASCII, on which line.
class StlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One triangle's three vertices, in the file's units (x, y, z each).
using StlTriangle = std::array<std::array<float, 3>, 3>;

// The triangles of `bytes`: binary when its size is exactly 84 + 50 x the
// triangle count at byte 80 (whatever its header says, as STLLoader decides),
// else ASCII ("solid NAME", then "facet normal n n n / outer loop / vertex x y z
// (3x) / endloop / endfacet" per triangle, "endsolid"; several solids may
// follow one another). Throws StlError when it is neither, when a number is
// not finite (NaN, inf, or beyond float), or when there is no triangle.
// Bounded by `bytes` itself: a binary count is believed only when the size
// matches it, and an ASCII triangle takes far more bytes than the 36 it is
// stored in, so memory stays below about twice the input's size. Reads from
// memory only (the caller bounds and reads the file; fuzz/stl_fuzzer.cc).
std::vector<StlTriangle> ReadStl(const std::string& bytes);

// The binary STL of `triangles`: an 80-byte header, the count, and per
// triangle its unit normal (right-handed from the vertex order; zero for a
// degenerate triangle), its vertices and a zero attribute word. Little-endian.
std::string WriteBinaryStl(const std::vector<StlTriangle>& triangles);

// Standard base64 (RFC 4648, with '=' padding).
std::string Base64(const std::string& bytes);

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_STL_H_
