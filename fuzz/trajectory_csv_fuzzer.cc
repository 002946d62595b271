// libFuzzer target for trajectory CSVs as `ccma view --trajectory=FILE.csv`
// reads them (viewer/view_frames.h on viewer/csv_reader.h; the CSV that
// `ccma trajectory --out` and `ccma plan --out` write), read against
// models/4dof_reduced.yaml.
//
// Any text must either give frames or be refused with
// ccma::viewer::ViewInputError naming the source; any other exception, a
// crash, a sanitizer report, a leak or a hang is a bug, and so are frames that
// break the contract (none, more than MaxViewFrames, a control of the wrong
// size or out of range, a point or time that is not finite).
//   scripts/fuzz.sh [seconds] trajectory_csv      live fuzzing (clang, sanitizers)
// The corpus fuzz/corpus_trajectory_csv/ is replayed by CTest
// fuzz_corpus_replay_trajectory_csv.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "ccma/limits.h"
#include "fuzz/fuzz_checks.h"
#include "viewer/view_frames.h"

namespace {

const char kSource[] = "fuzz_trajectory.csv";

void CheckFrames(const ccma::Model& model, const std::vector<ccma::viewer::ViewFrame>& frames) {
  if (frames.empty() || frames.size() > static_cast<std::size_t>(ccma::viewer::MaxViewFrames(model))) {
    ccma_fuzz::Fail("frame count " + std::to_string(frames.size()) + " out of range");
  }
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const ccma::viewer::ViewFrame& f = frames[i];
    const bool controls = f.controls.size() == model.num_controls() && f.controls.allFinite() &&
                          (f.controls.size() == 0 || f.controls.cwiseAbs().maxCoeff() <= ccma::kMaxMagnitude);
    if (!controls) ccma_fuzz::Fail("controls of the wrong size or out of range", std::to_string(i));
    const bool points = (!f.commanded || f.commanded->allFinite()) && (!f.tracked || f.tracked->allFinite());
    if (!points || !std::isfinite(f.time)) ccma_fuzz::Fail("a point or time that is not finite", std::to_string(i));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const ccma::Model& model = ccma_fuzz::RepositoryModel("models/4dof_reduced.yaml");
  std::vector<ccma::viewer::ViewFrame> frames;
  if (ccma_fuzz::ReadOrRefuse<ccma::viewer::ViewInputError>(
          kSource, [&] { frames = ccma::viewer::FramesFromTrajectoryText(model, text, kSource); })) {
    CheckFrames(model, frames);
  }
  return 0;
}
