#include "formats/internal/link_inertial.h"

#include <cmath>

#include "formats/model_loader.h"

namespace ccma::internal {

void SetLinkInertial(double mass, const Eigen::Isometry3d& X_LI, const Eigen::Matrix3d& I_I, const std::string& where,
                     RobotLink* link) {
  if (!std::isfinite(mass) || !X_LI.matrix().allFinite() || !I_I.allFinite()) {
    throw ModelError(where + ": inertial: mass, origin and inertia must be finite numbers");
  }
  const Eigen::Isometry3d X_WI = link->X_WL * X_LI;
  link->mass = mass;
  link->com_W = X_WI.translation();
  link->inertia_W = X_WI.linear() * I_I * X_WI.linear().transpose();
}

}  // namespace ccma::internal
