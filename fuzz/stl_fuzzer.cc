// libFuzzer target for the STL reader of `ccma view --meshes` (viewer/stl.h).
//
// Any bytes must either read as triangles or be refused with StlError; any
// other exception (std::bad_alloc from a trusted count included), a crash, a
// sanitizer report, a leak or a hang is a bug. What is read must be sound:
// at least one triangle, every coordinate finite, and the canonical binary
// STL written from it must read back to the same triangles.
//   Build: stl_fuzzer.cc with viewer/stl.cc only (the reader has no other
//   dependency), -fsanitize=fuzzer,address,undefined.
// Seed corpus: fuzz/corpus_stl/ (a tiny binary and ASCII STL, a header
// claiming 1e9 triangles, a NaN vertex, a truncated file, ...), replayed
// through this function by fuzz/corpus_replay.cc like the loader's.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "viewer/stl.h"

namespace {

[[noreturn]] void Bug(const char* what) {
  std::fprintf(stderr, "stl_fuzzer: %s\n", what);
  std::abort();
}

// The triangles read: some, all finite, and written back losslessly.
void CheckRead(const std::vector<ccma::viewer::StlTriangle>& triangles) {
  if (triangles.empty()) Bug("read no triangles without an error");
  for (const auto& t : triangles) {
    for (const auto& v : t) {
      for (float x : v) {
        if (!std::isfinite(x)) Bug("read a coordinate that is not finite");
      }
    }
  }
  const std::string binary = ccma::viewer::WriteBinaryStl(triangles);
  if (binary.size() != 84 + 50 * triangles.size()) Bug("written binary STL has the wrong size");
  if (ccma::viewer::ReadStl(binary) != triangles) Bug("written binary STL reads back differently");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    CheckRead(ccma::viewer::ReadStl(bytes));
  } catch (const ccma::viewer::StlError& e) {
    if (std::string(e.what()).empty()) Bug("an StlError without a message");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "unexpected exception: %s\n", e.what());
    std::abort();
  } catch (...) {
    Bug("unexpected non-standard exception");
  }
  return 0;
}
