// libFuzzer target for the MuJoCo MJCF reader and the importer (issue "trust
// boundaries").
//
// Any input must either import or be rejected with ccma::ModelError naming
// the source; any other exception, a crash, a sanitizer report, a leak, a
// hang or a file opened by MuJoCo (an <include> or a mesh followed) is a bug. The
// corpus fuzz/corpus_mjcf/ holds exported robots and the hostile cases
// of issue 51.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "analyses/robot_import.h"
#include "fuzz/fuzz_checks.h"
#include "formats/model_loader.h"
#include "formats/mjcf_reader.h"

namespace {

constexpr const char* kSource = "fuzz.xml";
// Assembling a large robot is the solver's business, not this target's.
constexpr std::size_t kMaxImportedLinks = 30;

void Run(const std::string& input) {
  const ccma::RobotDescription robot = ccma::ReadMjcfFromString(input, kSource, {});
  if (robot.source != kSource) ccma_fuzz::Fail("wrong source", robot.source);
  if (robot.links.size() > kMaxImportedLinks) return;
  ccma::ImportOptions options;
  if (!robot.has_end_effector && !robot.links.empty()) options.end_effector_link = robot.links.back().name;
  const ccma::ImportedRobot imported = ccma::ImportRobot(robot, options);
  if (imported.model.num_bodies() == 0) ccma_fuzz::Fail("imported a model without bodies", imported.yaml);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  ccma_fuzz::ReadOrRefuse<ccma::ModelError>({kSource}, /*one_printable_line=*/true, [&] { Run(input); });
  return 0;
}
