// Editing model-file text in tests.
#ifndef CCMA_TESTS_MODEL_TEXT_H_
#define CCMA_TESTS_MODEL_TEXT_H_

#include <functional>
#include <regex>
#include <string>

#include <Eigen/Core>

#include "formats/model_loader.h"

namespace ccma::testing {

// Adds `rpy: [...]` (from rpy_for(body name)) to every flow-style body entry
// `{name: X, position: [...]}`. Mobile bases (they have `pose`) are untouched.
inline std::string WithBodyRpy(const std::string& text,
                               const std::function<Eigen::Vector3d(const std::string&)>& rpy_for) {
  const std::regex body(R"(\{name: (\w+), position: (\[[^\]]*\])\})");
  std::string out;
  size_t last = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), body); it != std::sregex_iterator();
       ++it) {
    const Eigen::Vector3d rpy = rpy_for((*it)[1].str());
    char buffer[128];
    std::snprintf(buffer, sizeof buffer, ", rpy: [%.17g, %.17g, %.17g]}", rpy.x(), rpy.y(), rpy.z());
    out += text.substr(last, it->position() - last);
    out += "{name: " + (*it)[1].str() + ", position: " + (*it)[2].str() + buffer;
    last = it->position() + it->length();
  }
  return out + text.substr(last);
}

// The loader's error message for model text `text` (named bad.yaml), or ""
// when it loads.
inline std::string LoadErrorOf(const std::string& text) {
  try {
    LoadModelFromString(text, "bad.yaml");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

}  // namespace ccma::testing

#endif  // CCMA_TESTS_MODEL_TEXT_H_
