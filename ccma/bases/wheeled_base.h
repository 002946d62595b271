// What the wheeled base types (omni and differential) share: the body stays
// on the floor, upright (OmniBasePlanarCost), and its motors drive x, y and
// heading (OmniBaseMotorCost); controls x [m], y [m], theta [rad].
#ifndef CCMA_BASES_WHEELED_BASE_H_
#define CCMA_BASES_WHEELED_BASE_H_

#include <vector>

#include "ccma/base_kind.h"

namespace ccma {
namespace internal {

class WheeledBaseKind : public BaseKind {
 public:
  const std::vector<BaseControl>& controls() const override;
  // The planar (4 rows) and motor (5 rows) constraints.
  std::vector<BaseConstraint> Constraints(const MobileBase& base, bool autodiff) const override;
  int num_residuals() const override;
};

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_BASES_WHEELED_BASE_H_
