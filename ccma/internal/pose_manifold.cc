#include "ccma/internal/pose_manifold.h"

#include <algorithm>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ccma/rotation.h"

namespace ccma {

bool PoseManifold::Plus(const double* x, const double* delta,
                        double* x_plus_delta) const {
  const Eigen::Quaterniond q{Eigen::Map<const Eigen::Vector4d>{x}};
  const Eigen::Quaterniond q_new =
      (QuaternionExp(Eigen::Map<const Eigen::Vector3d>{delta}) * q).normalized();
  Eigen::Map<Eigen::Vector4d>{x_plus_delta} = q_new.coeffs();
  for (int i = 0; i < 3; ++i) x_plus_delta[4 + i] = x[4 + i] + delta[3 + i];
  return true;
}

bool PoseManifold::PlusJacobian(const double* /*x*/, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 7, 6, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.topRows<6>().setIdentity();
  return true;
}

bool PoseManifold::RightMultiplyByPlusJacobian(const double* /*x*/, int num_rows,
                                               const double* ambient_matrix,
                                               double* tangent_matrix) const {
  // (rows x 7) * [I6; 0] keeps the first six columns.
  for (int r = 0; r < num_rows; ++r) {
    std::copy(ambient_matrix + 7 * r, ambient_matrix + 7 * r + 6, tangent_matrix + 6 * r);
  }
  return true;
}

bool PoseManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  const Eigen::Quaterniond qy{Eigen::Map<const Eigen::Vector4d>{y}};
  const Eigen::Quaterniond qx{Eigen::Map<const Eigen::Vector4d>{x}};
  Eigen::Map<Eigen::Vector3d>{y_minus_x} = QuaternionLog(qy * qx.conjugate());
  for (int i = 0; i < 3; ++i) y_minus_x[3 + i] = y[4 + i] - x[4 + i];
  return true;
}

bool PoseManifold::MinusJacobian(const double* /*x*/, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 6, 7, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.leftCols<6>().setIdentity();
  return true;
}

}  // namespace ccma
