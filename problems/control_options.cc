#include <string>

#include "ccma/internal/format.h"
#include "ccma/internal/in_range.h"
#include "problems/control_problem.h"

namespace ccma {
namespace {


}  // namespace

bool ControlOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (!(lambda > 0 && lambda < 1)) return fail("lambda must lie in (0, 1), got " + FormatG(lambda));
  if (!InRange(max_step_m, 1e-6, 1e3)) {
    return fail("max_step_m must lie in [1e-6, 1000] (m), got " + FormatG(max_step_m));
  }
  if (!InRange(max_step_rad, 1e-6, 10)) {
    return fail("max_step_rad must lie in [1e-6, 10] (rad), got " + FormatG(max_step_rad));
  }
  if (!InRange(max_iterations, 1, 100000)) {
    return fail("max_iterations must lie in [1, 100000], got " + std::to_string(max_iterations));
  }
  if (!InRange(target_tolerance, 1e-14, 1)) {
    return fail("target_tolerance must lie in [1e-14, 1] (m or rad), got " + FormatG(target_tolerance));
  }
  if (!InRange(finite_difference_step, 1e-12, 1e-1)) {
    return fail("finite_difference_step must lie in [1e-12, 0.1] (m or rad), got " +
                FormatG(finite_difference_step));
  }
  const Secondary& sec = secondary;
  if (!InRange(sec.singularity_weight, 0, 1e6)) {
    return fail("secondary.singularity_weight must lie in [0, 1e6], got " + FormatG(sec.singularity_weight));
  }
  if (!InRange(sec.singularity_threshold, 1e-6, 100)) {
    return fail("secondary.singularity_threshold must lie in [1e-6, 100] (m or rad per control unit), got " +
                FormatG(sec.singularity_threshold));
  }
  if (!InRange(sec.pivot_weight, 0, 1e6)) {
    return fail("secondary.pivot_weight must lie in [0, 1e6], got " + FormatG(sec.pivot_weight));
  }
  if (!InRange(sec.pivot_threshold, 1e-9, 1)) {
    return fail("secondary.pivot_threshold must lie in [1e-9, 1], got " + FormatG(sec.pivot_threshold));
  }
  if (!InRange(sec.spread_weight, 0, 1e6)) {
    return fail("secondary.spread_weight must lie in [0, 1e6] (1/m^2), got " + FormatG(sec.spread_weight));
  }
  if (!InRange(sec.clearance_m, 1e-3, 100)) {
    return fail("secondary.clearance_m must lie in [0.001, 100] (m), got " + FormatG(sec.clearance_m));
  }
  if (!InRange(sec.travel_weight, 0, 1e6)) {
    return fail("secondary.travel_weight must lie in [0, 1e6], got " + FormatG(sec.travel_weight));
  }
  if (!InRange(sec.iterations, 1, 100)) {
    return fail("secondary.iterations must lie in [1, 100], got " + std::to_string(sec.iterations));
  }
  if (!InRange(sec.sigma_step, 1e-8, 1e-2)) {
    return fail("secondary.sigma_step must lie in [1e-8, 0.01] (m or rad), got " + FormatG(sec.sigma_step));
  }
  std::string forward_why;
  if (!forward.IsValid(&forward_why)) return fail("forward." + forward_why);
  return true;
}

}  // namespace ccma
