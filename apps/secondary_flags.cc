// The flags of singularity-aware control and redundancy resolution
// (ControlOptions::Secondary, problems/control_problem.h), shared by
// `ccma control` and `ccma trajectory`, and the "secondary" block of their
// JSON.
#include <algorithm>
#include <cmath>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "ccma/internal/format.h"

DEFINE_double(singularity_weight, 0,
              "weight of the barrier keeping the smallest singular value of dX/du above "
              "--singularity_threshold, resolved in the null space of the end-effector task; 0 = off, "
              "0..1e6 [1]");
DEFINE_double(singularity_threshold, 0.1,
              "smallest singular value of dX/du below which the barrier acts, 1e-6..100 [m or rad per control unit]");
DEFINE_double(pivot_weight, 0,
              "weight of the barrier keeping the pivot ratio of dG/ds (the JSON's dG_ds_pivot_ratio) above "
              "--pivot_threshold, resolved in the null space of the end-effector task; 0 = off, 0..1e6 [1]");
DEFINE_double(pivot_threshold, 1e-3,
              "pivot ratio of dG/ds below which its barrier acts, 1e-9..1 [1, dimensionless]");
DEFINE_string(secondary, "none",
              "secondary objective for redundant systems, resolved in the null space of the end-effector "
              "task: none, spread (keep bases --clearance_m apart), sigma (the singularity barrier with "
              "--secondary_weight), travel (least base travel from the start) [none|spread|sigma|travel]");
DEFINE_double(secondary_weight, 1.0, "weight of --secondary, 0..1e6 [1/m^2 for spread and travel, 1 for sigma]");
DEFINE_double(clearance_m, 0.5, "--secondary=spread: distance below which bases are pushed apart, 0.001..100 [m]");

namespace ccma::cli {

const std::vector<std::string>& SecondaryFlagNames() {
  // A function, not a global: the command registry may be built before
  // this file's globals are.
  static const std::vector<std::string> names = {"singularity_weight", "singularity_threshold", "pivot_weight",
                                                 "pivot_threshold",    "secondary",             "secondary_weight",
                                                 "clearance_m"};
  return names;
}

void ApplySecondaryFlags(ControlOptions* options) {
  auto in = [](double v, double lo, double hi) { return v >= lo && v <= hi; };  // false for NaN
  if (!in(FLAGS_singularity_weight, 0, 1e6)) {
    throw UsageError("--singularity_weight: " + FormatG(FLAGS_singularity_weight) + " must lie in [0, 1e6]");
  }
  if (!in(FLAGS_singularity_threshold, 1e-6, 100)) {
    throw UsageError("--singularity_threshold: " + FormatG(FLAGS_singularity_threshold) +
                     " must lie in [1e-6, 100] (m or rad per control unit)");
  }
  if (!in(FLAGS_pivot_weight, 0, 1e6)) {
    throw UsageError("--pivot_weight: " + FormatG(FLAGS_pivot_weight) + " must lie in [0, 1e6]");
  }
  if (!in(FLAGS_pivot_threshold, 1e-9, 1)) {
    throw UsageError("--pivot_threshold: " + FormatG(FLAGS_pivot_threshold) + " must lie in [1e-9, 1]");
  }
  if (!in(FLAGS_secondary_weight, 0, 1e6)) {
    throw UsageError("--secondary_weight: " + FormatG(FLAGS_secondary_weight) + " must lie in [0, 1e6]");
  }
  if (!in(FLAGS_clearance_m, 1e-3, 100)) {
    throw UsageError("--clearance_m: " + FormatG(FLAGS_clearance_m) + " must lie in [0.001, 100] (m)");
  }
  ControlOptions::Secondary& s = options->secondary;
  s.singularity_weight = FLAGS_singularity_weight;
  s.singularity_threshold = FLAGS_singularity_threshold;
  s.pivot_weight = FLAGS_pivot_weight;
  s.pivot_threshold = FLAGS_pivot_threshold;
  s.clearance_m = FLAGS_clearance_m;
  if (FLAGS_secondary == "spread") {
    s.spread_weight = FLAGS_secondary_weight;
  } else if (FLAGS_secondary == "sigma") {
    s.singularity_weight = std::max(s.singularity_weight, FLAGS_secondary_weight);
  } else if (FLAGS_secondary == "travel") {
    s.travel_weight = FLAGS_secondary_weight;
  } else if (FLAGS_secondary != "none") {
    throw UsageError("--secondary: " + Quote(FLAGS_secondary) + " is not none, spread, sigma or travel");
  }
}

}  // namespace ccma::cli
