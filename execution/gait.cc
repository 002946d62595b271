#include "execution/gait.h"

#include <cmath>

namespace ccma {

bool Gait::IsValid(std::string* why) const {
  auto fail = [why](const std::string& text) {
    if (why != nullptr) *why = text;
    return false;
  };
  if (!(hz > 0 && hz <= 100)) return fail("gait frequency must be in (0, 100] Hz");
  if (!(bob_m >= 0 && bob_m <= 1)) return fail("gait bob must be in [0, 1] m");
  if (!(sway_rad >= 0 && sway_rad <= 0.5)) return fail("gait sway must be in [0, 0.5] rad");
  return true;
}

bool HasLeggedBases(const Model& model) {
  for (const MobileBase& base : model.mobile_bases) {
    if (base.type == BaseType::kLegged) return true;
  }
  return false;
}

void ApplyGait(const Model& model, const Gait& gait, double t, const Eigen::VectorXd& set_velocity,
               Eigen::VectorXd* controls) {
  const double phase = 2 * M_PI * gait.hz * t;
  for (int k = 0; k < model.num_bases(); ++k) {
    if (model.mobile_bases[static_cast<size_t>(k)].type != BaseType::kLegged) continue;
    const int i = model.base_control(k);
    // Standing still (no x, y motion) a quadruped does not step.
    if (std::hypot(set_velocity[i], set_velocity[i + 1]) <= 1e-9) continue;
    (*controls)[i + 3] += gait.bob_m * std::sin(phase);
    (*controls)[i + 4] += gait.sway_rad * std::sin(phase);
  }
}

}  // namespace ccma
