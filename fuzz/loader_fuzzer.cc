// libFuzzer target for the model loader (issue "hostile input").
//
// Any text must either load or be rejected with ccma::ModelError; any other
// exception, a crash, a sanitizer report, a leak or a hang is a bug.
//   scripts/fuzz.sh [seconds] loader      live fuzzing (clang, sanitizers)
// The corpus in fuzz/corpus_loader/ is also replayed through this function by
// every test run (fuzz/corpus_replay.cc, CTest `fuzz_corpus_replay_loader`).
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
    // A loaded model is internally consistent: it has an actuator (a mobile
    // base or an actuated joint) and its end-effector is on one of its bodies.
    if (model.name.empty() || model.num_bases() + model.num_actuated_joints() == 0 ||
        model.end_effector.body < 0 || model.end_effector.body >= model.num_bodies()) {
      std::fprintf(stderr, "loaded an inconsistent model\n");
      std::abort();
    }
    // Warnings (unknown keys, implausible magnitudes) name the file too.
    for (const std::string& w : warnings) {
      if (w.rfind("fuzz.yaml", 0) != 0) {
        std::fprintf(stderr, "warning without the file name: %s\n", w.c_str());
        std::abort();
      }
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
