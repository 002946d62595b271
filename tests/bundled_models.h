// The bundled model files (models/*.yaml) by name, for tests that run over
// every one of them: a model added to models/ is tested without editing the test.
#ifndef CCMA_TESTS_BUNDLED_MODELS_H_
#define CCMA_TESTS_BUNDLED_MODELS_H_

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace ccma::testing {

// The stems of models/*.yaml, sorted.
inline std::vector<std::string> BundledModels() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(CCMA_MODELS_DIR)) {
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace ccma::testing

#endif  // CCMA_TESTS_BUNDLED_MODELS_H_
