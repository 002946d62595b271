// Masses and loads of a model (model_format.md, "Masses and loads"): what
// `ccma statics` weighs, and the limits it compares efforts with. A model
// file without these keys has no mass anywhere and no limits.
//
// Units: kg, m, N, N*m, m/s^2.
#ifndef CCMA_MASS_PROPERTIES_H_
#define CCMA_MASS_PROPERTIES_H_

#include <Eigen/Core>

namespace ccma {

// A point mass fixed in a body.
struct MassProperties {
  double mass = 0;                                   // kg, >= 0
  Eigen::Vector3d com_B = Eigen::Vector3d::Zero();   // centre of mass in the body frame [m]
};

// lower <= effort <= upper for an actuated joint [N*m or N] (`effort_limits`).
struct EffortLimits {
  bool given = false;
  double lower = 0, upper = 0;
};

}  // namespace ccma

#endif  // CCMA_MASS_PROPERTIES_H_
