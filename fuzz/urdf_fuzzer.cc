// libFuzzer target for the URDF reader, its closure file and the importer
// (issue "trust boundaries").
//
// The input is a URDF, optionally followed by a line `--- closures ---` and
// the text of its closure file. Any input must either import or be rejected
// with ccma::ModelError naming one of the two sources; any other exception,
// a crash, a sanitizer report, a leak or a hang is a bug. The corpus
// fuzz/corpus_urdf/ holds small real robots and the hostile cases of issue 34.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "analyses/robot_import.h"
#include "fuzz/fuzz_checks.h"
#include "formats/closure_file.h"
#include "formats/model_loader.h"
#include "formats/urdf_reader.h"

namespace {

constexpr const char* kUrdf = "fuzz.urdf";
constexpr const char* kClosures = "fuzz.closures.yaml";
constexpr const char* kSeparator = "\n--- closures ---\n";
// Assembling a large robot is the solver's business, not this target's.
constexpr std::size_t kMaxImportedLinks = 30;

void Run(const std::string& input) {
  const std::size_t split = input.find(kSeparator);
  const std::string urdf = input.substr(0, split);
  ccma::RobotDescription robot = ccma::ReadUrdfFromString(urdf, kUrdf);
  if (robot.source != kUrdf) ccma_fuzz::Fail("wrong source", robot.source);
  if (split != std::string::npos) {
    const std::string closures = input.substr(split + std::char_traits<char>::length(kSeparator));
    ccma::ApplyClosureFile(ccma::ParseClosureFile(closures, kClosures), &robot);
  }
  if (robot.links.size() > kMaxImportedLinks) return;
  ccma::ImportOptions options;
  if (!robot.links.empty()) options.end_effector_link = robot.links.back().name;
  const ccma::ImportedRobot imported = ccma::ImportRobot(robot, options);
  if (imported.model.num_bodies() == 0) ccma_fuzz::Fail("imported a model without bodies", imported.yaml);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  ccma_fuzz::ReadOrRefuse<ccma::ModelError>({kUrdf, kClosures}, /*one_printable_line=*/true, [&] { Run(input); });
  return 0;
}
