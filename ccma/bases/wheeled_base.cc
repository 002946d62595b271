#include "ccma/bases/wheeled_base.h"

#include "cost_functions/omni_base_motor_cost.h"
#include "cost_functions/omni_base_planar_cost.h"

namespace ccma {
namespace internal {

const std::vector<BaseControl>& WheeledBaseKind::controls() const {
  static const std::vector<BaseControl> controls = {{"x", "m"}, {"y", "m"}, {"theta", "rad"}};
  return controls;
}

std::vector<BaseConstraint> WheeledBaseKind::Constraints(const MobileBase& /*base*/, bool autodiff) const {
  std::vector<BaseConstraint> out(2);
  out[0].cost.reset(autodiff ? MakeOmniBasePlanarAutoDiff() : new OmniBasePlanarCost());
  out[0].part = "planar";
  out[1].cost.reset(autodiff ? MakeOmniBaseMotorAutoDiff() : new OmniBaseMotorCost());
  out[1].reads_controls = true;
  out[1].part = "motor";
  return out;
}

int WheeledBaseKind::num_residuals() const {
  return OmniBasePlanarCost::kNumResiduals + OmniBaseMotorCost::kNumResiduals;
}

}  // namespace internal
}  // namespace ccma
