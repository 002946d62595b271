#include "ccma/mass_properties.h"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "ccma/internal/format.h"

namespace ccma {

bool IsPhysicalInertia(const Eigen::Matrix3d& inertia, std::string* why) {
  if (!inertia.allFinite()) {
    *why = "must be finite";
    return false;
  }
  const double scale = std::max(1e-300, inertia.cwiseAbs().maxCoeff());
  const double tolerance = 1e-9 * scale;
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > tolerance) {
    *why = "must be symmetric";
    return false;
  }
  const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
  if (moments.minCoeff() < -tolerance) {
    *why = "must be positive semi-definite (a principal moment is " + FormatG(moments.minCoeff()) + " kg*m^2)";
    return false;
  }
  for (int i = 0; i < 3; ++i) {
    if (moments[i] > moments[(i + 1) % 3] + moments[(i + 2) % 3] + tolerance) {
      *why = "violates the triangle inequality: principal moment " + FormatG(moments[i]) +
             " kg*m^2 exceeds the sum of the other two (" + FormatG(moments[(i + 1) % 3]) + " + " +
             FormatG(moments[(i + 2) % 3]) + ")";
      return false;
    }
  }
  return true;
}

}  // namespace ccma
