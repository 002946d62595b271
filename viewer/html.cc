#include "viewer/html.h"

#include <stdexcept>

#include "viewer/bundle.h"

namespace ccma::viewer {
namespace {

std::string EscapeHtml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

bool HasBundle() { return internal::kBundleSize > 0; }

std::string ViewerHtml(const std::string& scene_json, const std::string& model_name) {
  if (!HasBundle()) {
    throw std::logic_error("this ccma was built without the viewer's JavaScript (three.js and esbuild could "
                           "not be fetched from the npm registry when it was configured; configure again with "
                           "access to the registry and rebuild)");
  }
  std::string html;
  html.reserve(internal::kBundleSize + scene_json.size() + 1024);
  html +=
      "<!DOCTYPE html>\n"
      "<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; script-src 'unsafe-inline'; "
      "style-src 'unsafe-inline'; img-src data: blob:\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>ccma view: ";
  html += EscapeHtml(model_name);
  html += "</title></head>\n<body>\n<script type=\"application/json\" id=\"ccma-scene\">";
  html += scene_json;  // BuildScene wrote <, > and & as \u escapes
  html += "</script>\n<script>";
  html.append(internal::kBundle, internal::kBundleSize);
  html += "</script>\n</body></html>\n";
  return html;
}

}  // namespace ccma::viewer
