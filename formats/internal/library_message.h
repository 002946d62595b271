// A parser library's own message (urdfdom, yaml-cpp) turned into part of
// ours: such messages quote bytes of the file (yaml-cpp's "unknown escape
// character: X"), so they are escaped as ccma::Printable does and cut.
#ifndef CCMA_FORMATS_INTERNAL_LIBRARY_MESSAGE_H_
#define CCMA_FORMATS_INTERNAL_LIBRARY_MESSAGE_H_

#include <string>

#include "ccma/internal/format.h"

namespace ccma {
namespace internal {

// `text` printable on one line (bytes outside printable ASCII as \xNN), at
// most 200 bytes of it, "..." when cut.
inline std::string LibraryMessage(const std::string& text) {
  constexpr std::size_t kMaxBytes = 200;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kMaxBytes; i += kQuotedChars) {
    out += Printable(text.substr(i, kQuotedChars));
  }
  return text.size() > kMaxBytes ? out + "..." : out;
}

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_LIBRARY_MESSAGE_H_
