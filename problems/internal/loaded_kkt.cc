#include "problems/internal/loaded_kkt.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "ccma/internal/joint_deviation.h"
#include "ccma/internal/joint_spring_directions.h"
#include "ccma/internal/pose_manifold.h"

namespace ccma {
namespace {

constexpr int kTan = kPoseTangentSize;
constexpr int kMaxKktBlockRows = 9;  // the most rows of one constraint block (cost_functions/)
using PatternTriplets = std::vector<Eigen::Triplet<double>>;
using PairMatrix = Eigen::Matrix<double, 12, 12>;

// Placeholder entries (value 0) for a rows x cols block at (row0, col0).
void AddPatternBlock(int row0, int col0, int rows, int cols, PatternTriplets* t) {
  for (int j = 0; j < cols; ++j) {
    for (int i = 0; i < rows; ++i) t->emplace_back(row0 + i, col0 + j, 0.0);
  }
}

// The index of entry (row, col) in a compressed matrix's values (the entry
// is in the pattern: a binary search of its outer vector).
template <typename Sparse>
int PatternIndex(const Sparse& M, int outer, int inner) {
  const int* begin = M.innerIndexPtr() + M.outerIndexPtr()[outer];
  const int* end = M.innerIndexPtr() + M.outerIndexPtr()[outer + 1];
  const int* at = std::lower_bound(begin, end, inner);
  if (at == end || *at != inner) throw std::logic_error("loaded KKT: an entry outside the pattern");
  return static_cast<int>(at - M.innerIndexPtr());
}

// d/ds of sum_r lambda_r D_r(s) over the rows of one compliant joint's
// directions (ccma/internal/joint_spring_directions.h: D = de/ds), over its
// two bodies (12 x 12, [body_a; body_b]): the curvature of its deviations
// weighted by what each row carries (k e on a spring, the multiplier on a
// rigid direction); g0 = D(s)^T lambda. Forward differences of the analytic
// directions (relative error about the step, 1e-6): it only shapes the
// iteration (its rate), never the equilibrium it converges to.
PairMatrix JointCurvature(const Joint& joint, const State& s, const Eigen::Matrix<double, 6, 1>& lambda, int rows,
                          const Eigen::Matrix<double, 12, 1>& g0) {
  constexpr double kStep = 1e-6;  // rad or m
  const int bodies[2] = {joint.body_a, joint.body_b};
  const PoseManifold manifold;
  PairMatrix out = PairMatrix::Zero();
  State at = s;  // only the perturbed body's pose changes, and is put back
  for (int side = 0; side < 2; ++side) {
    if (bodies[side] == kWorld) continue;
    double* pose = at.pose(bodies[side]);
    const Eigen::Matrix<double, kPoseAmbientSize, 1> original = Eigen::Map<const Eigen::Matrix<double, kPoseAmbientSize, 1>>(pose);
    for (int k = 0; k < kTan; ++k) {
      double delta[6] = {0, 0, 0, 0, 0, 0};
      delta[k] = kStep;
      manifold.Plus(original.data(), delta, pose);
      const Eigen::Matrix<double, 12, 1> g = JointSpringDirections(joint, at).D.topRows(rows).transpose() * lambda.head(rows);
      out.col(kTan * side + k) = (g - g0) / kStep;
    }
    std::copy(original.data(), original.data() + kPoseAmbientSize, pose);
  }
  return out;
}

}  // namespace

LoadedKkt::LoadedKkt(const Model& model, const ConstraintSet& set) : signature_(Signature(model, set)) {
  // The row order is CompliantEquilibrium's: read it from one built at the
  // home state (its values are not used).
  const CompliantEquilibrium sys(model, set, State::Home(model), model.home_controls(),
                                 CompliantEquilibrium::Factorization::kNone);
  n_ = sys.state_size();
  N_ = sys.size();
  m_ = static_cast<int>(sys.A().rows());
  compliant_ = sys.compliant_controls();
  k_ = sys.k();
  stiffest_ = k_.size() > 0 ? std::max(1.0, k_.maxCoeff()) : 1.0;
  set_rows_ = sys.set_rows();
  set_size_ = set.num_rows();
  delta_of_control_.assign(static_cast<size_t>(model.num_controls()), -1);
  for (size_t i = 0; i < compliant_.size(); ++i) delta_of_control_[static_cast<size_t>(compliant_[i])] = static_cast<int>(i);
  std::vector<int> a_row_of_set_row(static_cast<size_t>(set.num_rows()), -1);
  for (size_t r = 0; r < set_rows_.size(); ++r) {
    if (set_rows_[r] >= 0) a_row_of_set_row[static_cast<size_t>(set_rows_[r])] = static_cast<int>(r);
  }
  for (const ConstraintBlock& block : set.blocks()) block_a_row_.push_back(a_row_of_set_row[static_cast<size_t>(block.row)]);
  for (size_t j = 0; j < model.joints.size(); ++j) {
    if (!model.joints[j].stiffness.has_springs()) continue;
    const CompliantJointRows& r = sys.joint_rows()[j];
    spring_joints_.push_back({static_cast<int>(j), r.a_row, r.s_row});
  }
  BuildPattern(model, set);
  g_.resize(m_);
  A_u_.setZero(m_, model.num_controls());
  e_.resize(k_.size());
  force_.resize(N_);
}

// What the layout depends on: the blocks' rows, bodies and controls, the
// joints' types, bodies and springs, every stiffness value.
std::vector<double> LoadedKkt::Signature(const Model& model, const ConstraintSet& set) {
  std::vector<double> out = {double(set.state_size()), double(set.num_rows()), double(set.num_controls()),
                             double(set.blocks().size())};
  for (const ConstraintBlock& block : set.blocks()) {
    out.insert(out.end(), {double(block.row), double(block.rows), double(block.control_offset),
                           double(block.control_size), double(block.bodies.size())});
    out.insert(out.end(), block.bodies.begin(), block.bodies.end());
  }
  for (const Joint& joint : model.joints) {
    out.insert(out.end(), {double(joint.type), double(joint.body_a), double(joint.body_b),
                           joint.actuated ? double(joint.control) : -1.0, joint.stiffness.axis,
                           double(joint.stiffness.translation.size()), double(joint.stiffness.rotation.size())});
    out.insert(out.end(), joint.stiffness.translation.begin(), joint.stiffness.translation.end());
    out.insert(out.end(), joint.stiffness.rotation.begin(), joint.stiffness.rotation.end());
  }
  for (const MobileBase& base : model.mobile_bases) {
    out.insert(out.end(), {double(base.stiffness.given()), base.stiffness.k[0], base.stiffness.k[1], base.stiffness.k[2]});
  }
  return out;
}

Eigen::VectorXd LoadedKkt::SetOrder(const Eigen::VectorXd& mu) const {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(set_size_);
  for (size_t r = 0; r < set_rows_.size(); ++r) {
    if (set_rows_[r] >= 0) w[set_rows_[r]] = mu[static_cast<Eigen::Index>(r)];
  }
  return w;
}

bool LoadedKkt::Fits(const Model& model, const ConstraintSet& set) const { return signature_ == Signature(model, set); }

void LoadedKkt::BuildPattern(const Model& model, const ConstraintSet& set) {
  PatternTriplets t;
  const auto rigid = [&](int a_row, int col0, int rows, int cols) {
    AddPatternBlock(N_ + a_row, col0, rows, cols, &t);
    AddPatternBlock(col0, N_ + a_row, cols, rows, &t);
  };
  const auto pair = [&](int a, int b) {
    for (const int p : {a, b}) {
      for (const int q : {a, b}) {
        if (p != kWorld && q != kWorld) AddPatternBlock(kTan * p, kTan * q, kTan, kTan, &t);
      }
    }
  };
  for (size_t b = 0; b < set.blocks().size(); ++b) {
    const ConstraintBlock& block = set.blocks()[b];
    if (block_a_row_[b] < 0) continue;
    for (const int body : block.bodies) {
      if (body != kWorld) rigid(block_a_row_[b], kTan * body, block.rows, kTan);
    }
    for (int c = block.control_offset; c >= 0 && c < block.control_offset + block.control_size; ++c) {
      const int d = delta_of_control_[static_cast<size_t>(c)];
      if (d >= 0) rigid(block_a_row_[b], n_ + d, block.rows, 1);
    }
    if (!block.bodies.empty()) pair(block.bodies[0], block.bodies.size() > 1 ? block.bodies[1] : kWorld);
  }
  for (const SpringJoint& spring : spring_joints_) {
    const Joint& joint = model.joints[static_cast<size_t>(spring.joint)];
    const int rigid_rows = TranslationSpringCount(joint.type) + RotationSpringCount(joint.type) -
                           (joint.stiffness.translation.empty() ? 0 : TranslationSpringCount(joint.type)) -
                           (joint.stiffness.rotation.empty() ? 0 : RotationSpringCount(joint.type));
    for (const int body : {joint.body_a, joint.body_b}) {
      if (body != kWorld && rigid_rows > 0) rigid(spring.a_row, kTan * body, rigid_rows, kTan);
    }
    pair(joint.body_a, joint.body_b);
  }
  for (int i = 0; i < N_ + m_; ++i) t.emplace_back(i, i, 0.0);
  for (int b = 0; b < n_ / kTan; ++b) AddPatternBlock(kTan * b, kTan * b, kTan, kTan, &t);
  // K is stored by its lower triangle (what the LDL^T reads).
  t.erase(std::remove_if(t.begin(), t.end(), [](const Eigen::Triplet<double>& e) { return e.row() < e.col(); }), t.end());
  K_.resize(N_ + m_, N_ + m_);
  K_.setFromTriplets(t.begin(), t.end());
  K_.makeCompressed();
  // A: the rigid rows of K's lower left.
  PatternTriplets a;
  for (int col = 0; col < N_; ++col) {
    for (Sparse::InnerIterator it(K_, col); it; ++it) {
      if (it.row() >= N_) a.emplace_back(it.row() - N_, col, 0.0);
    }
  }
  A_.resize(m_, N_);
  A_.setFromTriplets(a.begin(), a.end());
  A_.makeCompressed();
}

template <typename SparseMatrix>
int LoadedKkt::Where(const SparseMatrix& M, int outer, int inner) {
  if (recording_) {
    tape_.push_back(PatternIndex(M, outer, inner));
    return tape_.back();
  }
  if (tape_position_ >= tape_.size()) throw std::logic_error("loaded KKT: the assembly changed its order");
  return tape_[tape_position_++];
}

template <typename Derived>
void LoadedKkt::AddToK(int row0, int col0, const Eigen::MatrixBase<Derived>& M) {
  for (Eigen::Index j = 0; j < M.cols(); ++j) {
    const int col = col0 + static_cast<int>(j);
    for (Eigen::Index i = std::max<Eigen::Index>(0, col - row0); i < M.rows(); ++i) {  // the lower triangle
      K_.valuePtr()[Where(K_, col, row0 + static_cast<int>(i))] += M(i, j);
    }
  }
}

template <typename Derived>
void LoadedKkt::AddRigid(int a_row, int col0, const Eigen::MatrixBase<Derived>& M) {
  AddToK(N_ + a_row, col0, M);  // (its transpose is in the upper triangle)
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    for (Eigen::Index j = 0; j < M.cols(); ++j) {
      A_.valuePtr()[Where(A_, a_row + static_cast<int>(i), col0 + static_cast<int>(j))] += M(i, j);
    }
  }
}

void LoadedKkt::AddPair(int body_a, int body_b, const PairMatrix& local) {
  const int bodies[2] = {body_a, body_b};
  for (int p = 0; p < 2; ++p) {
    for (int q = 0; q < 2; ++q) {
      if (bodies[p] == kWorld || bodies[q] == kWorld) continue;
      AddToK(kTan * bodies[p], kTan * bodies[q], local.block<kTan, kTan>(kTan * p, kTan * q));
    }
  }
}

void LoadedKkt::Assemble(const Model& model, const ConstraintSet& set, const LoadedPoint& x, const Eigen::VectorXd& u,
                         const ExternalWrench& wrench, const Eigen::VectorXd& w, const Eigen::VectorXd& mu,
                         double eps_H, double eps_A) {
  matrices_ = true;
  K_.coeffs().setZero();
  A_.coeffs().setZero();
  recording_ = tape_.empty();
  tape_position_ = 0;
  eps_H_ = eps_H;
  Evaluate(model, set, x, u, wrench, w, mu);
  for (int i = 0; i < N_; ++i) K_.coeffRef(i, i) += eps_H;
  for (int i = 0; i < m_; ++i) K_.coeffRef(N_ + i, N_ + i) -= eps_A;
  if (tape_position_ != (recording_ ? 0 : tape_.size())) throw std::logic_error("loaded KKT: the assembly changed its order");
}

void LoadedKkt::AssembleResiduals(const Model& model, const ConstraintSet& set, const LoadedPoint& x,
                                  const Eigen::VectorXd& u, const ExternalWrench& wrench, const Eigen::VectorXd& mu) {
  matrices_ = false;
  reaction_.setZero(N_);
  Evaluate(model, set, x, u, wrench, Eigen::VectorXd(), mu);
}

void LoadedKkt::Evaluate(const Model& model, const ConstraintSet& set, const LoadedPoint& x, const Eigen::VectorXd& u,
                         const ExternalWrench& wrench, const Eigen::VectorXd& w, const Eigen::VectorXd& mu) {
  force_.setZero();
  Eigen::VectorXd u_eff = u;
  for (size_t i = 0; i < compliant_.size(); ++i) u_eff[compliant_[i]] += x.delta[static_cast<Eigen::Index>(i)];
  AssembleBlocks(set, x.s, u_eff, w, mu);
  AssembleSprings(model, x.s, mu);
  // The compliant controls' springs: e = delta, k on the diagonal.
  for (size_t i = 0; i < compliant_.size(); ++i) {
    const int d = static_cast<int>(i);
    e_[d] = x.delta[d];
    force_[n_ + d] -= k_[d] * e_[d];
    if (matrices_) K_.valuePtr()[Where(K_, n_ + d, n_ + d)] += k_[d];
  }
  // The loads and how their moments turn with the bodies (-dQ/ds).
  force_.head(n_) += GeneralizedLoads(model, x.s, wrench);
  if (!matrices_) return;
  const std::vector<Eigen::Matrix3d> turning = GeneralizedLoadsJacobianBlocks(model, x.s, wrench);
  for (size_t b = 0; b < turning.size(); ++b) {
    const Eigen::Matrix3d symmetric = -0.5 * (turning[b] + turning[b].transpose());  // (as the curvature's)
    AddToK(kTan * static_cast<int>(b), kTan * static_cast<int>(b), symmetric);
  }
}

// reaction_ += the block's rows' A^T mu (mu in A's order, or empty: none),
// from its Jacobians (EvaluateInFrames' storage: poses, then controls).
void LoadedKkt::AddReaction(const ConstraintBlock& block, int a_row, const double* const* jacobians,
                            const Eigen::VectorXd& mu) {
  using AmbientJacobian = Eigen::Matrix<double, Eigen::Dynamic, kPoseAmbientSize, Eigen::RowMajor, kMaxKktBlockRows>;
  using ControlJacobian = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, kMaxKktBlockRows, kMaxBaseControls>;
  if (mu.size() == 0) return;
  const Eigen::VectorXd mu_block = mu.segment(a_row, block.rows);
  for (int p = 0; p < block.num_poses; ++p) {
    if (block.bodies[p] == kWorld) continue;
    const Eigen::Map<const AmbientJacobian> J(jacobians[p], block.rows, kPoseAmbientSize);
    reaction_.segment<kTan>(kTan * block.bodies[p]).noalias() += J.leftCols<kTan>().transpose() * mu_block;
  }
  if (block.control_size == 0) return;
  const Eigen::Map<const ControlJacobian> J_u(jacobians[block.num_poses], block.rows, block.control_size);
  for (int c = 0; c < block.control_size; ++c) {
    const int d = delta_of_control_[static_cast<size_t>(block.control_offset + c)];
    if (d >= 0) reaction_[n_ + d] += J_u.col(c).dot(mu_block);
  }
}

// The constraint blocks that are rigid rows (every block but a compliant
// joint's own): g, A and the rows' curvature weighted by w.
void LoadedKkt::AssembleBlocks(const ConstraintSet& set, const State& s, const Eigen::VectorXd& u_eff,
                               const Eigen::VectorXd& w, const Eigen::VectorXd& mu) {
  using AmbientJacobian = Eigen::Matrix<double, Eigen::Dynamic, kPoseAmbientSize, Eigen::RowMajor, kMaxKktBlockRows>;
  using ControlJacobian = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, kMaxKktBlockRows, kMaxBaseControls>;
  BodyFrames frames;
  set.ComputeFrames(s, &frames);
  double jac_storage[3][kMaxKktBlockRows * kPoseAmbientSize];
  double residuals[kMaxKktBlockRows];
  const double* params[3];
  const BodyFrame* block_frames[2];
  for (size_t b = 0; b < set.blocks().size(); ++b) {
    const ConstraintBlock& block = set.blocks()[b];
    const int a_row = block_a_row_[b];
    if (a_row < 0) continue;
    const int poses = block.num_poses;
    for (int p = 0; p < poses; ++p) params[p] = ConstraintSet::Pose(s, block.bodies[p]);
    params[poses] = block.control_size > 0 ? u_eff.data() + block.control_offset : nullptr;
    double* jacobians[3] = {jac_storage[0], jac_storage[1], jac_storage[2]};
    ConstraintSet::BlockFrames(block, frames, block_frames);
    block.framed->EvaluateInFrames(block_frames, params, residuals, jacobians);
    g_.segment(a_row, block.rows) = Eigen::Map<const Eigen::VectorXd>(residuals, block.rows);
    if (!matrices_) {
      AddReaction(block, a_row, jacobians, mu);
      continue;
    }
    for (int p = 0; p < poses; ++p) {
      if (block.bodies[p] == kWorld) continue;
      const Eigen::Map<const AmbientJacobian> J(jac_storage[p], block.rows, kPoseAmbientSize);
      AddRigid(a_row, kTan * block.bodies[p], J.leftCols<kTan>());
    }
    if (block.control_size > 0) {
      const Eigen::Map<const ControlJacobian> J_u(jac_storage[poses], block.rows, block.control_size);
      A_u_.block(a_row, block.control_offset, block.rows, block.control_size) = J_u;
      for (int c = 0; c < block.control_size; ++c) {
        const int d = delta_of_control_[static_cast<size_t>(block.control_offset + c)];
        if (d >= 0) AddRigid(a_row, n_ + d, J_u.col(c));
      }
    }
    PairMatrix local = PairMatrix::Zero();
    block.framed->AddWeightedHessianInFrames(block_frames, params, w.data() + block.row,
                                             local.topLeftCorner(kTan * poses, kTan * poses));
    AddPair(block.bodies[0], poses > 1 ? block.bodies[1] : kWorld, local);
  }
}

// The compliant joints: their rigid directions (g, A), their springs (e,
// the force S^T k e, S^T k S) and their directions' curvature.
void LoadedKkt::AssembleSprings(const Model& model, const State& s, const Eigen::VectorXd& mu) {
  for (const SpringJoint& spring : spring_joints_) {
    const Joint& joint = model.joints[static_cast<size_t>(spring.joint)];
    const SpringDirections d = JointSpringDirections(joint, s);
    const Eigen::VectorXd deviation = JointDeviation(joint, s);
    Eigen::Matrix<double, 6, 1> lambda = Eigen::Matrix<double, 6, 1>::Zero();
    Eigen::Matrix<double, 12, 1> pull = Eigen::Matrix<double, 12, 1>::Zero(), reaction = pull;
    PairMatrix local = PairMatrix::Zero();
    int a = spring.a_row, s_row = spring.s_row;
    for (int i = 0; i < d.rows(); ++i) {
      const bool translation = i < d.translations;
      const bool is_spring = !(translation ? joint.stiffness.translation : joint.stiffness.rotation).empty();
      const Eigen::Matrix<double, 1, 12> D = d.D.row(i);
      if (is_spring) {
        e_[s_row] = deviation[i];
        lambda[i] = k_[s_row] * e_[s_row];
        pull += D.transpose() * lambda[i];
        if (matrices_) local += k_[s_row] * D.transpose() * D;
        ++s_row;
      } else {
        g_[a] = deviation[i];
        lambda[i] = mu.size() > a ? mu[a] : 0.0;
        if (!matrices_) reaction.noalias() += D.transpose() * lambda[i];
        if (matrices_ && joint.body_a != kWorld) AddRigid(a, kTan * joint.body_a, D.leftCols<kTan>());
        if (matrices_ && joint.body_b != kWorld) AddRigid(a, kTan * joint.body_b, D.rightCols<kTan>());
        ++a;
      }
    }
    if (joint.body_a != kWorld) force_.segment<kTan>(kTan * joint.body_a) -= pull.head<kTan>();
    if (joint.body_b != kWorld) force_.segment<kTan>(kTan * joint.body_b) -= pull.tail<kTan>();
    if (!matrices_) {
      if (joint.body_a != kWorld) reaction_.segment<kTan>(kTan * joint.body_a) += reaction.head<kTan>();
      if (joint.body_b != kWorld) reaction_.segment<kTan>(kTan * joint.body_b) += reaction.tail<kTan>();
      continue;
    }
    // The curvature's symmetric part: its skew part is the rotations' own
    // (world-frame increments compose on the left), 0 at an equilibrium,
    // and the LDL^T takes one triangle.
    const PairMatrix curvature =
        JointCurvature(joint, s, lambda, d.rows(), d.D.topRows(d.rows()).transpose() * lambda.head(d.rows()));
    local += 0.5 * (curvature + curvature.transpose());
    AddPair(joint.body_a, joint.body_b, local);
  }
}

}  // namespace ccma
