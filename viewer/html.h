// The one self-contained HTML page of `ccma view`: the fixed shell of
// viewer/scene_format.md with the scene and the JavaScript bundle (three.js
// included, built from viewer/js/ by CMake) inlined. A Content-Security-Policy
// of default-src 'none' makes the page unable to fetch anything.
#ifndef CCMA_VIEWER_HTML_H_
#define CCMA_VIEWER_HTML_H_

#include <string>

namespace ccma::viewer {

// Whether this build carries the JavaScript bundle (CMake fetched three.js and esbuild).
bool HasBundle();

// The page for a scene (BuildScene). The title is "ccma view: <model_name>"
// (HTML-escaped). Throws std::logic_error when !HasBundle().
std::string ViewerHtml(const std::string& scene_json, const std::string& model_name);

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_HTML_H_
