// libFuzzer target for obstacles files (`--obstacles=FILE`,
// formats/obstacles_file.h), read against examples/obstacles/pillar_detour.yaml
// (4dof_reduced with one obstacle, `pillar`, so that a name can clash).
//
// Any text must either add its obstacles or be refused with ccma::ModelError
// naming the source; any other exception, a crash, a sanitizer report, a leak
// or a hang is a bug, and so is an added obstacle that breaks the contract
// (a name taken twice, a number out of range, more than kMaxObstacles).
//   scripts/fuzz.sh [seconds] obstacles       live fuzzing (clang, sanitizers)
// The corpus fuzz/corpus_obstacles/ is replayed by CTest fuzz_corpus_replay_obstacles.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "ccma/limits.h"
#include "formats/obstacles_file.h"
#include "fuzz/fuzz_checks.h"

namespace {

const char kSource[] = "fuzz_obstacles.yaml";

// What every obstacle of a model that took the file must satisfy.
void CheckObstacles(const ccma::Model& before, const ccma::Model& model) {
  const std::vector<ccma::Obstacle>& all = model.collision.obstacles;
  if (!model.collision.enabled) ccma_fuzz::Fail("obstacles added but clearance is off");
  if (all.size() < before.collision.obstacles.size() || all.size() > std::size_t{ccma::kMaxObstacles}) {
    ccma_fuzz::Fail("obstacle count " + std::to_string(all.size()) + " out of range");
  }
  std::set<std::string> names{"world"};
  for (const ccma::Body& body : model.bodies) names.insert(body.name);
  for (const ccma::Obstacle& o : all) {
    if (!names.insert(o.name).second) ccma_fuzz::Fail("a name taken twice", o.name);
    const bool finite = o.center.allFinite() && o.size.allFinite() && std::isfinite(o.radius) &&
                        std::isfinite(o.yaw) && std::isfinite(o.z_min) && std::isfinite(o.z_max);
    if (!finite || o.center.cwiseAbs().maxCoeff() > ccma::kMaxMagnitude || !(o.z_min <= o.z_max)) {
      ccma_fuzz::Fail("obstacle with a number out of range", o.name);
    }
    const bool cylinder = o.shape == ccma::ObstacleShape::kCylinder;
    if (cylinder ? !(o.radius > 0) : !(o.size.minCoeff() > 0)) ccma_fuzz::Fail("obstacle of no size", o.name);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const ccma::Model& base = ccma_fuzz::RepositoryModel("examples/obstacles/pillar_detour.yaml");
  ccma::Model model = base;
  std::vector<std::string> warnings;
  const bool added = ccma_fuzz::ReadOrRefuse<ccma::ModelError>(
      kSource, [&] { ccma::AddObstaclesFromString(text, kSource, &model, &warnings); });
  if (added) {
    CheckObstacles(base, model);
  } else if (model.collision.obstacles.size() != base.collision.obstacles.size()) {
    ccma_fuzz::Fail("a refused file changed the model's obstacles");
  }
  // Warnings (unknown keys, implausible magnitudes) name the file too.
  for (const std::string& w : warnings) ccma_fuzz::ExpectNamesSource(w, kSource);
  return 0;
}
