// The viewer's JavaScript (viewer/js/, three.js included), embedded in the
// library at build time by cmake/embed_text.cmake; empty when three.js and
// esbuild could not be fetched when the build was configured.
#ifndef CCMA_VIEWER_BUNDLE_H_
#define CCMA_VIEWER_BUNDLE_H_

#include <cstddef>

namespace ccma::viewer::internal {

extern const char* const kBundle;
extern const std::size_t kBundleSize;

}  // namespace ccma::viewer::internal

#endif  // CCMA_VIEWER_BUNDLE_H_
