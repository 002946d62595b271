// libFuzzer target for waypoint files (`--waypoints=FILE.csv` of
// `ccma trajectory` and `ccma plan`, formats/waypoints.h).
//
// Any text must either give waypoints or be refused with ccma::WaypointError
// naming the source; any other exception, a crash, a sanitizer report, a leak
// or a hang is a bug, and so are waypoints that break the contract (none, more
// than kMaxWaypoints, a time going back, a number out of range).
//   scripts/fuzz.sh [seconds] waypoints       live fuzzing (clang, sanitizers)
// The corpus fuzz/corpus_waypoints/ is replayed by CTest fuzz_corpus_replay_waypoints.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "ccma/limits.h"
#include "formats/waypoints.h"
#include "fuzz/fuzz_checks.h"

namespace {

const char kSource[] = "fuzz_waypoints.csv";

void CheckWaypoints(const std::vector<ccma::Waypoint>& waypoints) {
  if (waypoints.empty() || waypoints.size() > std::size_t{ccma::kMaxWaypoints}) {
    ccma_fuzz::Fail("waypoint count " + std::to_string(waypoints.size()) + " out of range");
  }
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const ccma::Waypoint& w = waypoints[i];
    if (!(std::abs(w.time) <= ccma::kMaxTime)) ccma_fuzz::Fail("time out of range", std::to_string(i));
    if (i > 0 && !(w.time >= waypoints[i - 1].time)) ccma_fuzz::Fail("time goes back", std::to_string(i));
    const bool in_range = w.position.allFinite() && w.rpy.allFinite() &&
                          w.position.cwiseAbs().maxCoeff() <= ccma::kMaxMagnitude &&
                          w.rpy.cwiseAbs().maxCoeff() <= ccma::kMaxMagnitude;
    if (!in_range) ccma_fuzz::Fail("pose out of range", std::to_string(i));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<ccma::Waypoint> waypoints;
  if (ccma_fuzz::ReadOrRefuse<ccma::WaypointError>(kSource, [&] { waypoints = ccma::ParseWaypoints(text, kSource); })) {
    CheckWaypoints(waypoints);
  }
  return 0;
}
