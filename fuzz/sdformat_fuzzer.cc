// libFuzzer target for the SDFormat reader and the importer (issue "trust
// boundaries").
//
// Any input must either import or be rejected with ccma::ModelError naming
// the source; any other exception, a crash, a sanitizer report, a leak, a
// hang or a file opened by libsdformat (an <include> followed) is a bug. The
// corpus fuzz/corpus_sdformat/ holds small real robots and the hostile cases
// of issue 34.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "analyses/robot_import.h"
#include "formats/model_loader.h"
#include "formats/sdformat_reader.h"

namespace {

constexpr const char* kSource = "fuzz.sdf";
// Assembling a large robot is the solver's business, not this target's.
constexpr std::size_t kMaxImportedLinks = 30;

[[noreturn]] void Bug(const char* what, const std::string& detail) {
  std::fprintf(stderr, "%s: %s\n", what, detail.c_str());
  std::abort();
}

void Run(const std::string& input) {
  const ccma::RobotDescription robot = ccma::ReadSdformatFromString(input, kSource, {});
  if (robot.source != kSource) Bug("wrong source", robot.source);
  if (robot.links.size() > kMaxImportedLinks) return;
  ccma::ImportOptions options;
  if (!robot.has_end_effector && !robot.links.empty()) options.end_effector_link = robot.links.back().name;
  const ccma::ImportedRobot imported = ccma::ImportRobot(robot, options);
  if (imported.model.num_bodies() == 0) Bug("imported a model without bodies", imported.yaml);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  try {
    Run(input);
  } catch (const ccma::ModelError& e) {
    const std::string message = e.what();
    if (message.rfind(kSource, 0) != 0) Bug("message without the file name", message);
    for (const char c : message) {
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) Bug("control character in a message", message);
    }
  } catch (const std::exception& e) {
    Bug("unexpected exception", e.what());
  } catch (...) {
    Bug("unexpected non-standard exception", "");
  }
  return 0;
}
