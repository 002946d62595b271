#include "problems/internal/step_constraints.h"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "ccma/internal/constraint_set.h"
#include "ccma/internal/format.h"
#include "ccma/joint_coordinates.h"
#include "ccma/rotation.h"
#include "cost_functions/actuated_prismatic_cost.h"
#include "cost_functions/actuated_revolute_cost.h"

namespace ccma {

double JointCoordinateGradient(const Model& model, const Joint& joint, const State& s, Eigen::RowVectorXd* dq_ds) {
  // The motor cost functions evaluate exactly the quantities q is made of
  // (at u = 0): their Jacobians give dq/ds without new derivative code.
  dq_ds->setZero(model.state_size());
  const double* poses[3] = {ConstraintSet::Pose(s, joint.body_a), ConstraintSet::Pose(s, joint.body_b), nullptr};
  const double zero = 0.0;
  poses[2] = &zero;
  double residuals[2];
  double J_A[2 * kPoseAmbientSize], J_B[2 * kPoseAmbientSize], J_u[2];
  double* jacobians[3] = {J_A, J_B, J_u};
  Eigen::Matrix<double, 1, 6> g_A, g_B;
  double q = 0;
  if (joint.type == JointType::kRevolute) {
    const ActuatedRevoluteCost cost(joint.e1_A, joint.e2_A, joint.w_B);
    cost.Evaluate(poses, residuals, jacobians);
    const double x = residuals[0] + 1.0, y = residuals[1];  // cos q, sin q (up to scale)
    const double norm2 = x * x + y * y;
    q = std::atan2(y, x);
    for (int c = 0; c < 6; ++c) {
      g_A[c] = (x * J_A[kPoseAmbientSize + c] - y * J_A[c]) / norm2;
      g_B[c] = (x * J_B[kPoseAmbientSize + c] - y * J_B[c]) / norm2;
    }
  } else {
    const ActuatedPrismaticCost cost(joint.p_A, joint.p_B, joint.a_A);
    cost.Evaluate(poses, residuals, jacobians);
    q = residuals[0];
    for (int c = 0; c < 6; ++c) {
      g_A[c] = J_A[c];
      g_B[c] = J_B[c];
    }
  }
  if (joint.body_a != kWorld) dq_ds->segment<6>(kPoseTangentSize * joint.body_a) += g_A;
  if (joint.body_b != kWorld) dq_ds->segment<6>(kPoseTangentSize * joint.body_b) += g_B;
  return q;
}

StepConstraints::StepConstraints(const Model& model, const std::vector<int>& effective)
    : model_(model), column_of_(static_cast<size_t>(model.num_controls()), -1) {
  for (size_t c = 0; c < effective.size(); ++c) column_of_[static_cast<size_t>(effective[c])] = static_cast<int>(c);
  for (int k = 0; k < model.num_bases(); ++k) {
    if (model.mobile_bases[k].type == BaseType::kDifferential) differential_.push_back(k);
  }
  for (int j = 0; j < static_cast<int>(model.joints.size()); ++j) {
    if (model.joints[j].limited) limited_.push_back(j);
  }
  u0_ = model.home_controls();
}

void StepConstraints::Begin(const Eigen::VectorXd& u0) { u0_ = u0; }

double StepConstraints::Lateral(const Eigen::VectorXd& u, int base, Eigen::Vector3d* gradient) const {
  const int i = kBaseControlSize * base;
  const double dx = u[i] - u0_[i], dy = u[i + 1] - u0_[i + 1];
  const double mid = u0_[i + 2] + 0.5 * WrapAngle(u[i + 2] - u0_[i + 2]);
  const double s = std::sin(mid), c = std::cos(mid);
  if (gradient != nullptr) *gradient << -s, c, 0.5 * (-c * dx - s * dy);
  return -s * dx + c * dy;
}

double StepConstraints::MaxLateral(const Eigen::VectorXd& u) const {
  double worst = 0;
  for (int k : differential_) worst = std::max(worst, std::abs(Lateral(u, k, nullptr)));
  return worst;
}

double StepConstraints::MaxLimitViolation(const State& s) const {
  double worst = 0;
  for (int j : limited_) {
    const Joint& joint = model_.joints[j];
    const double q = JointCoordinate(joint, s);
    worst = std::max({worst, joint.lower - q, q - joint.upper});
  }
  return worst;
}

std::vector<int> StepConstraints::JointsAtOrBeyond(const State& s, double tolerance) const {
  std::vector<int> out;
  for (int j : limited_) {
    const Joint& joint = model_.joints[j];
    const double q = JointCoordinate(joint, s);
    if (q <= joint.lower + tolerance || q >= joint.upper - tolerance) out.push_back(j);
  }
  return out;
}

LinearConstraints StepConstraints::Linearize(const Eigen::VectorXd& u, const State& s, const Eigen::MatrixXd& ds_du,
                                             const std::vector<int>& active) const {
  const int k = static_cast<int>(ds_du.cols());
  LinearConstraints out;
  out.A.setZero(static_cast<Eigen::Index>(differential_.size() + active.size()), k);
  out.b.setZero(out.A.rows());
  int row = 0;
  for (int base : differential_) {
    Eigen::Vector3d gradient;
    out.b[row] = -Lateral(u, base, &gradient);
    for (int c = 0; c < 3; ++c) {
      const int column = column_of_[static_cast<size_t>(kBaseControlSize * base + c)];
      if (column >= 0) out.A(row, column) = gradient[c];
    }
    ++row;
  }
  Eigen::RowVectorXd dq_ds;
  for (int j : active) {
    const Joint& joint = model_.joints[j];
    const double q = JointCoordinateGradient(model_, joint, s, &dq_ds);
    const double bound = std::abs(q - joint.lower) < std::abs(q - joint.upper) ? joint.lower : joint.upper;
    out.A.row(row) = dq_ds * ds_du;
    out.b[row] = bound - q;
    ++row;
  }
  return out;
}

std::vector<int> StepConstraints::WouldCross(const State& s, const Eigen::MatrixXd& ds_du, const Eigen::VectorXd& d,
                                             double tolerance) const {
  std::vector<int> out;
  Eigen::RowVectorXd dq_ds;
  for (int j : limited_) {
    const Joint& joint = model_.joints[j];
    const double q = JointCoordinateGradient(model_, joint, s, &dq_ds) + (dq_ds * ds_du).dot(d);
    if (q < joint.lower - tolerance || q > joint.upper + tolerance) out.push_back(j);
  }
  return out;
}

std::string StepConstraints::Describe(const State& s, const std::vector<int>& active) const {
  std::string text;
  for (int j : active) {
    const Joint& joint = model_.joints[j];
    const double q = JointCoordinate(joint, s);
    const bool upper = std::abs(q - joint.upper) < std::abs(q - joint.lower);
    text += std::string(text.empty() ? "" : ", ") + "joint '" + joint.name + "' at its " +
            (upper ? "upper" : "lower") + " limit " + FormatG(upper ? joint.upper : joint.lower) +
            (joint.type == JointType::kRevolute ? " rad" : " m");
  }
  return text;
}

Eigen::VectorXd ConstrainedLmStep(const Eigen::MatrixXd& JtJ, const Eigen::VectorXd& Jtr, double mu,
                                  const LinearConstraints& constraints,
                                  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>* JtJ_eigen) {
  // -V (Lambda + mu)^-1 V^T g: least norm in the directions J does not see.
  // Eigenvalues below 1e-12 of the largest are rounding noise of J^T J (its
  // null space: redundant controls), and so is g there: those components are
  // dropped rather than amplified by 1 / mu, so that the step is the
  // least-norm one whichever way J^T J was formed.
  auto damped_solve = [mu](const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& eig, const Eigen::VectorXd& g) {
    const Eigen::VectorXd sigma_sq = eig.eigenvalues().cwiseMax(0.0);
    const double cutoff = 1e-12 * sigma_sq.maxCoeff();
    const Eigen::VectorXd projected = eig.eigenvectors().transpose() * g;
    Eigen::VectorXd scaled(projected.size());
    for (int i = 0; i < projected.size(); ++i) {
      scaled[i] = sigma_sq[i] > cutoff ? projected[i] / (sigma_sq[i] + mu) : 0.0;
    }
    return Eigen::VectorXd(-eig.eigenvectors() * scaled);
  };
  if (constraints.rows() == 0) {
    if (JtJ_eigen != nullptr) return damped_solve(*JtJ_eigen, Jtr);
    if (JtJ.rows() > kMaxEigenSolveSize) {
      // Many controls: a pivoted LDLT of J^T J + mu (k^3 / 3, against ~9 k^3
      // for the eigen-decomposition), without the cut-off above.
      Eigen::MatrixXd damped = JtJ;
      damped.diagonal().array() += mu;
      return -damped.ldlt().solve(Jtr);
    }
    return damped_solve(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(JtJ), Jtr);
  }
  const int k = static_cast<int>(JtJ.cols());
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(constraints.A, Eigen::ComputeFullV | Eigen::ComputeFullU);
  const Eigen::VectorXd sigma = svd.singularValues();
  const double cutoff = 1e-10 * std::max(1.0, sigma.size() > 0 ? sigma[0] : 0.0);
  int rank = 0;
  while (rank < sigma.size() && sigma[rank] > cutoff) ++rank;
  const Eigen::MatrixXd V = svd.matrixV(), U = svd.matrixU();
  const Eigen::VectorXd d0 =
      V.leftCols(rank) * (sigma.head(rank).cwiseInverse().asDiagonal() * (U.leftCols(rank).transpose() * constraints.b));
  const Eigen::MatrixXd N = V.rightCols(k - rank);
  if (N.cols() == 0) return d0;
  // min over z of |J N z + (J d0 + r)|^2 + mu |d0 + N z|^2, least norm in z:
  // (J N)^T (J N) = N^T J^T J N and (J N)^T (J d0 + r) = N^T (J^T J d0 + J^T r).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(N.transpose() * JtJ * N);
  const Eigen::VectorXd g = N.transpose() * (JtJ * d0 + Jtr + mu * d0);
  return d0 + N * damped_solve(eig, g);
}

}  // namespace ccma
