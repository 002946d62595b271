// Editing model-file text in tests.
#ifndef CCMA_TESTS_MODEL_TEXT_H_
#define CCMA_TESTS_MODEL_TEXT_H_

#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

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

// The text of the bundled model models/<stem>.yaml.
inline std::string ReadModel(const std::string& stem) {
  std::ifstream in(std::string(CCMA_MODELS_DIR) + "/" + stem + ".yaml");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// `text` with the i-th occurrence of `what` followed by `extra` (i = 0, 1, ...).
inline std::string InsertAfterEach(std::string text, const std::string& what, const std::vector<std::string>& extra) {
  size_t at = 0;
  for (const std::string& e : extra) {
    at = text.find(what, at);
    EXPECT_NE(at, std::string::npos) << what;
    if (at == std::string::npos) return text;
    at += what.size();
    text.insert(at, e);
    at += e.size();
  }
  return text;
}

// A motor (revolute about y at the origin, k1) turns a hub; a beam is welded
// to it at x = a (rotation k2, optionally translation kt); a tip force F
// down at x = L. Beam theory of rigid links on rotational springs:
//   tip deflection = F (L^2 / k1 + (L - a)^2 / k2 + 1 / kt).
inline std::string Cantilever(double k1, double a, const std::string& weld, double L) {
  std::ostringstream m;
  m.precision(17);
  m << "name: cantilever\ngravity: [0, 0, 0]\nbodies:\n  - {name: hub, position: [" << a / 2 << ", 0, 0]}\n"
    << "  - {name: beam, position: [" << (a + L) / 2 << ", 0, 0]}\njoints:\n"
    << "  - {name: motor, type: revolute, actuated: true, stiffness: " << k1
    << ", between: [world, hub], point: [0, 0, 0], axis: [0, 1, 0]}\n"
    << "  - {name: weld, type: fixed, between: [hub, beam], point: [" << a << ", 0, 0], stiffness: " << weld << "}\n"
    << "end_effector: {body: beam, point: [" << L << ", 0, 0], controlled: [x, z, pitch]}\n";
  return m.str();
}

}  // namespace ccma::testing

#endif  // CCMA_TESTS_MODEL_TEXT_H_
