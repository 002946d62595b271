// The constraint rows and controls shared by the wheeled base types (omni and
// differential): the body stays on the floor, upright (OmniBasePlanarCost),
// and its motors drive x, y and heading (OmniBaseMotorCost).
#ifndef CCMA_BASES_WHEELED_BASE_H_
#define CCMA_BASES_WHEELED_BASE_H_

#include <vector>

#include "ccma/base_kind.h"

namespace ccma {
namespace internal {

// x [m], y [m], theta [rad].
const std::vector<BaseControl>& WheeledBaseControls();
// The planar (4 rows) and motor (5 rows) constraints of a wheeled base.
std::vector<BaseConstraint> WheeledBaseConstraints(bool autodiff);
int WheeledBaseResidualCount();

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_BASES_WHEELED_BASE_H_
