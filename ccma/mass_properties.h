// Masses and loads of a model (model_format.md, "Masses and loads"): what
// `ccma statics` weighs, and the limits it compares efforts with. A model
// file without these keys has no mass anywhere and no limits.
//
// Units: kg, m, N, N*m, m/s^2.
#ifndef CCMA_MASS_PROPERTIES_H_
#define CCMA_MASS_PROPERTIES_H_

#include <string>

#include <Eigen/Core>

namespace ccma {

// A mass fixed in a body: statics weighs it at its centre of mass; dynamics
// also turns its inertia (model_format.md, "Inertia").
struct MassProperties {
  double mass = 0;                                   // kg, >= 0
  Eigen::Vector3d com_B = Eigen::Vector3d::Zero();   // centre of mass in the body frame [m]
  // About the centre of mass, in the body's axes [kg m^2]: symmetric positive
  // semi-definite, each principal moment at most the sum of the other two.
  // Zero: a point mass.
  Eigen::Matrix3d inertia_B = Eigen::Matrix3d::Zero();
};

// `inertia` (the file's [ixx, iyy, izz, ixy, ixz, iyz]) is a physical inertia
// tensor: symmetric positive semi-definite and each principal moment at most
// the sum of the other two, both to a tolerance of 1e-9 times its largest
// moment. `why` says which fails.
bool IsPhysicalInertia(const Eigen::Matrix3d& inertia, std::string* why);

// lower <= effort <= upper for an actuated joint [N*m or N] (`effort_limits`).
struct EffortLimits {
  bool given = false;
  double lower = 0, upper = 0;
};

}  // namespace ccma

#endif  // CCMA_MASS_PROPERTIES_H_
