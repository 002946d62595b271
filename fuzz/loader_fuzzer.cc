// libFuzzer target for the model loader (issue "hostile input").
//
// Any text must either load or be rejected with ccma::ModelError; any other
// exception, a crash, a sanitizer report, a leak or a hang is a bug.
//   fuzz/run_fuzz.sh [seconds]
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "formats/model_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> warnings;
  try {
    const ccma::Model model = ccma::LoadModelFromString(text, "fuzz.yaml", &warnings);
    // A loaded model is internally consistent.
    if (model.name.empty() || model.mobile_bases.empty() || model.end_effector.body < 0 ||
        model.end_effector.body >= model.num_bodies()) {
      std::fprintf(stderr, "loaded an inconsistent model\n");
      std::abort();
    }
  } catch (const ccma::ModelError& e) {
    // Messages start with the source name.
    if (std::string(e.what()).rfind("fuzz.yaml", 0) != 0) {
      std::fprintf(stderr, "message without the file name: %s\n", e.what());
      std::abort();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "unexpected exception: %s\n", e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "unexpected non-standard exception\n");
    std::abort();
  }
  return 0;
}
