#include "problems/internal/compliant_equilibrium.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "ccma/internal/joint_spring_directions.h"
#include "ccma/limits.h"

namespace ccma {
namespace {

constexpr double kCompliantRankThreshold = 1e-10;  // relative, as equilibrium.h

void CheckCompliantSize(long rows, long cols, const char* what) {
  if (rows * cols > kMaxStaticsEntries) {
    throw std::invalid_argument(std::string("statics: ") + std::to_string(rows) + " " + what + " x " +
                                std::to_string(cols) + " coordinates exceed " + std::to_string(kMaxStaticsEntries) +
                                " entries");
  }
}

// Rows of A and S a spring joint adds: its rigid and its spring directions.
void CountJointRows(const Joint& joint, int* rigid, int* springs) {
  const int t = TranslationSpringCount(joint.type), r = RotationSpringCount(joint.type);
  const int spring = (joint.stiffness.translation.empty() ? 0 : t) + (joint.stiffness.rotation.empty() ? 0 : r);
  *springs += spring;
  *rigid += t + r - spring;
}

// The stiffness of compliant control c (N/m or N*m/rad).
double ControlStiffness(const Model& model, int c) {
  int first = 0;
  for (const MobileBase& base : model.mobile_bases) {
    const int n = KindOf(base).num_controls();
    if (c < first + n) return c - first < 3 ? base.stiffness.k[c - first] : 0.0;
    first += n;
  }
  for (const Joint& joint : model.joints) {
    if (joint.actuated && joint.control == c) return joint.stiffness.axis;
  }
  return 0;
}

}  // namespace

std::vector<int> CompliantEquilibrium::CompliantControls(const Model& model) {
  std::vector<int> out;
  for (int b = 0; b < model.num_bases(); ++b) {
    // `stiffness` [kx, ky, ktheta]: a base's first three controls (a legged
    // base's height, roll and pitch stay rigid).
    if (!model.mobile_bases[static_cast<size_t>(b)].stiffness.given()) continue;
    for (int i = 0; i < 3; ++i) out.push_back(model.base_control(b) + i);
  }
  for (const Joint& joint : model.joints) {
    if (joint.actuated && joint.stiffness.axis > 0) out.push_back(joint.control);
  }
  return out;
}

CompliantEquilibrium::CompliantEquilibrium(const Model& model, const ConstraintSet& set, const State& s,
                                           const Eigen::VectorXd& u, Factorization factorization)
    : n_(set.state_size()), delta_of_control_(static_cast<size_t>(model.num_controls()), -1) {
  compliant_ = CompliantControls(model);
  std::vector<double> control_k;
  for (const int c : compliant_) {
    delta_of_control_[static_cast<size_t>(c)] = static_cast<int>(control_k.size());
    control_k.push_back(ControlStiffness(model, c));
  }
  int rows = set.num_rows(), springs = static_cast<int>(compliant_.size());
  for (size_t j = 0, b = 0; j < model.joints.size(); ++j) {
    const Joint& joint = model.joints[j];
    if (joint.stiffness.has_springs()) {
      rows -= set.blocks()[b].rows;
      CountJointRows(joint, &rows, &springs);
    }
    b += joint.actuated ? 2 : 1;
  }
  const int N = n_ + static_cast<int>(compliant_.size());
  CheckCompliantSize(rows, N, "rigid rows");
  CheckCompliantSize(springs, N, "springs");
  CheckCompliantSize(N, N, "variables");
  A_ = Eigen::MatrixXd::Zero(rows, N);
  A_u_ = Eigen::MatrixXd::Zero(rows, model.num_controls());
  S_ = Eigen::MatrixXd::Zero(springs, N);
  k_ = Eigen::VectorXd::Zero(springs);
  for (size_t i = 0; i < compliant_.size(); ++i) {
    S_(static_cast<int>(i), n_ + static_cast<int>(i)) = 1.0;
    k_[static_cast<int>(i)] = control_k[i];
  }
  Eigen::VectorXd C;
  Eigen::MatrixXd J_s, J_u;
  set.Evaluate(s, u, &C, &J_s, &J_u);
  AddBlocks(model, set, J_s, J_u, s);
  if (factorization != Factorization::kNone) Factorize(factorization);
}

void CompliantEquilibrium::AddBlocks(const Model& model, const ConstraintSet& set, const Eigen::MatrixXd& J_s,
                                     const Eigen::MatrixXd& J_u, const State& s) {
  int a_row = 0, s_row = static_cast<int>(compliant_.size());
  set_rows_.assign(static_cast<size_t>(A_.rows()), -1);
  auto add_block = [&](const ConstraintBlock& block) {
    A_.block(a_row, 0, block.rows, n_) = J_s.middleRows(block.row, block.rows);
    A_u_.middleRows(a_row, block.rows) = J_u.middleRows(block.row, block.rows);
    for (int r = 0; r < block.rows; ++r) set_rows_[static_cast<size_t>(a_row + r)] = block.row + r;
    for (int c = block.control_offset; c >= 0 && c < block.control_offset + block.control_size; ++c) {
      const int d = delta_of_control_[static_cast<size_t>(c)];
      if (d >= 0) A_.block(a_row, n_ + d, block.rows, 1) = J_u.block(block.row, c, block.rows, 1);
    }
    a_row += block.rows;
  };
  size_t b = 0;
  for (const Joint& joint : model.joints) {
    CompliantJointRows r;
    r.a_row = a_row;
    r.s_row = s_row;
    if (!joint.stiffness.has_springs()) {
      add_block(set.blocks()[b]);
    } else {
      const SpringDirections d = JointSpringDirections(joint, s);
      for (int i = 0; i < d.rows(); ++i) {
        const bool translation = i < d.translations;
        const std::vector<double>& values = translation ? joint.stiffness.translation : joint.stiffness.rotation;
        Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(A_.cols());
        if (joint.body_a != kWorld) row.segment<6>(6 * joint.body_a) = d.D.block<1, 6>(i, 0);
        if (joint.body_b != kWorld) row.segment<6>(6 * joint.body_b) = d.D.block<1, 6>(i, 6);
        if (values.empty()) {
          A_.row(a_row++) = row;
        } else {
          S_.row(s_row) = row;
          k_[s_row++] = values[static_cast<size_t>(translation ? i : i - d.translations)];
        }
      }
    }
    r.a_rows = a_row - r.a_row;
    r.s_rows = s_row - r.s_row;
    ++b;
    r.motor_row = a_row;
    if (joint.actuated) add_block(set.blocks()[b++]);
    r.motor_rows = a_row - r.motor_row;
    if (r.a_rows > 0) groups_.emplace_back(r.a_row, r.a_rows);
    if (r.motor_rows > 0) groups_.emplace_back(r.motor_row, r.motor_rows);
    joint_rows_.push_back(r);
  }
  for (; b < set.blocks().size(); ++b) add_block(set.blocks()[b]);
}

void CompliantEquilibrium::Factorize(Factorization factorization) {
  const int N = size();
  Eigen::MatrixXd Z;
  int rank = 0;
  if (A_.rows() > 0) {
    cod_.setThreshold(kCompliantRankThreshold);
    cod_.compute(A_.transpose());
    rank = static_cast<int>(cod_.rank());
  }
  // null(A): the columns of A^T's Q beyond its rank.
  Z = A_.rows() > 0 ? cod_.leftNullSpace() : Eigen::MatrixXd::Identity(N, N);
  const Eigen::MatrixXd M = S_ * Z;
  if (M.size() > 0) {
    // The motions the springs stretch (M's pivots above kCompliantRankThreshold
    // times the largest) and the rest. Column-pivoting QR: M has a column per
    // free motion of the rigid rows, hundreds on a large compliant model
    // (benchmarks/RESULTS.md, "Rank decisions").
    const RankRevealingDecomposition stretched(M, {0.0, kCompliantRankThreshold},
                                               RankRevealingDecomposition::Method::kPivotedQr);
    Z1_ = Z * stretched.rowSpace();
    Z0_ = Z * stretched.nullSpace();
  } else {
    Z1_.resize(N, 0);
    Z0_ = Z;
  }
  if (factorization == Factorization::kIdleMotions) return;
  const Eigen::MatrixXd B = S_ * Z1_;
  K1_.compute(B.transpose() * k_.asDiagonal() * B);
  if (factorization == Factorization::kFull) determinate_ = Determinate(rank);
}

// null(A^T) = P Z^T [0; I] of the decomposition A^T P = Q [T 0; 0 0] Z; a
// null vector that moves no joint's reaction and no effort only reshuffles
// what a base's planar and motor rows hold (both lock its tilt), which
// nothing reports.
bool CompliantEquilibrium::Determinate(int rank) const {
  const int m = static_cast<int>(A_.rows());
  if (rank == m) return true;
  const Eigen::MatrixXd kernel = cod_.nullSpace();  // m x (m - rank)
  const double scale = std::max(1.0, std::max(A_.cwiseAbs().maxCoeff(), A_u_.size() ? A_u_.cwiseAbs().maxCoeff() : 0.0));
  const double tolerance = 1e-8 * scale;
  if (A_u_.size() > 0 && (A_u_.transpose() * kernel).cwiseAbs().maxCoeff() > tolerance) return false;
  for (const auto& [row, count] : groups_) {
    if ((A_.middleRows(row, count).transpose() * kernel.middleRows(row, count)).cwiseAbs().maxCoeff() > tolerance) {
      return false;
    }
  }
  return true;
}

Eigen::VectorXd CompliantEquilibrium::Displacement(const Eigen::VectorXd& f) const {
  if (Z1_.cols() == 0) return Eigen::VectorXd::Zero(size());
  return Z1_ * K1_.solve(Z1_.transpose() * f);
}

Eigen::VectorXd CompliantEquilibrium::Displacement(const Eigen::VectorXd& f, const Eigen::MatrixXd& extra,
                                                   bool* newton) const {
  *newton = false;
  if (Z1_.cols() == 0) return Eigen::VectorXd::Zero(size());
  const Eigen::MatrixXd B = S_ * Z1_;
  // Not symmetric off equilibrium (the loads' moments turn with the
  // bodies): solved as it is, and taken only where its symmetric part is
  // positive definite.
  const Eigen::MatrixXd K = B.transpose() * k_.asDiagonal() * B + Z1_.transpose() * extra * Z1_;
  const Eigen::LDLT<Eigen::MatrixXd> symmetric(0.5 * (K + K.transpose()));
  if (symmetric.info() != Eigen::Success || !(symmetric.vectorD().minCoeff() > 0)) return Displacement(f);
  *newton = true;
  return Z1_ * MinimumNormSolver(K).solve(Z1_.transpose() * f);
}

Eigen::VectorXd CompliantEquilibrium::SpringForce(const Eigen::VectorXd& y) const {
  return S_.transpose() * (k_.asDiagonal() * (S_ * y));
}

Eigen::VectorXd CompliantEquilibrium::Multipliers(const Eigen::VectorXd& y, const Eigen::VectorXd& f) const {
  if (A_.rows() == 0) return Eigen::VectorXd();
  return cod_.solve(SpringForce(y) - f);
}

Eigen::VectorXd CompliantEquilibrium::Efforts(const Eigen::VectorXd& Q, double* unbalanced) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(size());
  f.head(Q.size()) = Q;
  const Eigen::VectorXd y = Displacement(f);
  const Eigen::VectorXd lambda = Multipliers(y, f);
  Eigen::VectorXd effort = lambda.size() > 0 ? Eigen::VectorXd(-A_u_.transpose() * lambda)
                                             : Eigen::VectorXd::Zero(static_cast<Eigen::Index>(delta_of_control_.size()));
  const Eigen::VectorXd stretch = k_.asDiagonal() * (S_ * y);  // the springs' forces
  for (size_t i = 0; i < compliant_.size(); ++i) effort[compliant_[i]] = -stretch[static_cast<Eigen::Index>(i)];
  if (unbalanced) {
    Eigen::VectorXd r = SpringForce(y) - f;
    if (lambda.size() > 0) r -= A_.transpose() * lambda;
    *unbalanced = r.size() > 0 ? r.lpNorm<Eigen::Infinity>() : 0.0;
  }
  return effort;
}

Eigen::MatrixXd CompliantEquilibrium::Compliance(const Eigen::MatrixXd& G) const {
  if (Z1_.cols() == 0) return Eigen::MatrixXd::Zero(G.rows(), G.rows());
  const Eigen::MatrixXd GZ = G * Z1_;
  const Eigen::MatrixXd C = GZ * K1_.solve(GZ.transpose());
  return 0.5 * (C + C.transpose());
}

int CompliantEquilibrium::MovedDirections(const Eigen::MatrixXd& G) const {
  if (Z1_.cols() == 0 || G.rows() == 0) return 0;
  const JacobiSvd svd(Eigen::MatrixXd((G * Z1_).transpose()));
  const Eigen::VectorXd& sigma = svd.singularValues();
  int rank = 0;
  while (rank < sigma.size() && sigma[rank] > kCompliantRankThreshold * sigma[0]) ++rank;
  return rank;
}

double CompliantEquilibrium::IdleForce(const Eigen::VectorXd& f) const {
  if (Z0_.cols() == 0) return 0.0;
  return (Z0_.transpose() * f).cwiseAbs().maxCoeff();
}

double CompliantEquilibrium::UnheldMotion(const Eigen::MatrixXd& G) const {
  if (Z0_.cols() == 0 || G.size() == 0) return 0.0;
  const double scale = std::max(1.0, G.cwiseAbs().maxCoeff());
  return (G * Z0_).cwiseAbs().maxCoeff() / scale;
}

}  // namespace ccma
