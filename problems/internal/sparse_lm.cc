#include "problems/internal/sparse_lm.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include "ccma/internal/pose_manifold.h"
#include "problems/internal/block_kernels.h"

namespace ccma {
namespace {

constexpr int kT = kPoseTangentSize;
constexpr int kA = kPoseAmbientSize;
constexpr int kMaxBlockRows = 9;  // the largest cost function (cost_functions/)

// Damping: Gauss-Newton (mu = 0) as long as its steps decrease E, which
// they do for every warm-started step; after a rejected step Marquardt's
// mu diag(J^T J), from kFirstDamping up by 10 per rejection, down by 10 per
// accepted step, back to 0 below kMinDamping.
constexpr double kFirstDamping = 1e-6;
constexpr double kMinDamping = 1e-10;
constexpr double kMaxDamping = 1e16;
// Marquardt's scaling D = diag(J^T J), clamped as Ceres clamps it.
constexpr double kMinDiagonal = 1e-6;
constexpr double kMaxDiagonal = 1e32;
// Convergence, all at rounding level so that two solvers that reach it
// agree to ~1e-13 (tests/forward_solvers_test.cc):
//  - E at or below kAssembledEnergyFloor: |C| ~ 4e-16, the rounding of the constraint
//    rows themselves (coordinates of order 1 m);
//  - the next step below kStepTolerance (m or rad);
//  - a relative decrease of E below kRelativeDecrease (a stationary point
//    with E > 0: Gauss-Newton converges linearly there, and the Newton
//    polish of forward_problem.cc takes over).
constexpr double kAssembledEnergyFloor = 1e-31;
constexpr double kStepTolerance = 1e-14;
constexpr double kRelativeDecrease = 1e-15;
// A step this small (m or rad) that does not lower E is rounding noise.
constexpr double kNoiseStep = 1e-12;
// A rigid image of a converged state (Solve's converged_energy) is accepted
// on its residuals alone, without Jacobians, when it is assembled to this
// level [m^2]: then the bound on |dE/ds| (RigidImageConverged) is at most
// |J|_F * 3e-13. Above it (a stationary point out of reach, E > 0, where the
// bound would say nothing) the gradient is evaluated.
constexpr double kRigidCheckEnergy = 1e-24;
// How much faster than |dc| / |ds| a chord step contracts the error at
// worst (measured on the paper's models: 3 to 15 times).
constexpr double kChordSafety = 30;
// Linear convergence (SparseLmSummary::linear): two accepted steps in a
// row whose successor is at least kLinearContraction times as long, at a
// steady rate (within a factor kRateSpread; the rate alternates between
// about 0.06 and 0.15 on the paper's models pulled out of reach, while near
// a solution it shrinks quadratically), with E above kStationaryEnergy
// (reachable solves pass 1e-20 on their way to 1e-31 with ratios ~ 1e-3).
constexpr double kLinearContraction = 0.05;
constexpr double kRateSpread = 4;
constexpr double kStationaryEnergy = 1e-20;

double NextDamping(double mu) { return mu == 0 ? kFirstDamping : 10 * mu; }

// The tangent Jacobian of one pose (Rows x 7 row-major as the cost
// functions write it; the tangent is the left 6 columns), read in place as
// its transpose: a column-major 6 x Rows matrix with outer stride 7. The
// fixed-size products J_a^T J_b = T_a T_b^T then run as vectorised sums of
// outer products (a copy into column-major Rows x 6 matrices first, and
// products of their transposes, took twice as long).
template <int Rows>
using TangentTranspose = Eigen::Map<const Eigen::Matrix<double, kT, Rows>, Eigen::Unaligned, Eigen::OuterStride<kA>>;
template <int Rows>
using Ambient = Eigen::Map<const Eigen::Matrix<double, Rows, kA, Eigen::RowMajor>>;

template <int Rows>
void AccumulateTerm(const double* jac0, const double* jac1, Eigen::Matrix<double, kT, kT>* diag0,
                    Eigen::Matrix<double, kT, kT>* diag1, Eigen::Matrix<double, kT, kT>* off,
                    bool off_transposed) {
  // Packed copies of the strided maps first: the products then run on
  // contiguous columns (a fifth fewer instructions than on the maps).
  using Packed = Eigen::Matrix<double, kT, Rows>;
  Packed T0, T1;
  if (jac0 != nullptr) {
    T0 = TangentTranspose<Rows>(jac0);
    diag0->noalias() += T0.lazyProduct(T0.transpose());
  }
  if (jac1 != nullptr) {
    T1 = TangentTranspose<Rows>(jac1);
    diag1->noalias() += T1.lazyProduct(T1.transpose());
  }
  if (off != nullptr) {
    if (off_transposed) {
      off->noalias() += T1.lazyProduct(T0.transpose());
    } else {
      off->noalias() += T0.lazyProduct(T1.transpose());
    }
  }
}

template <int Rows>
void GradientTerm(const double* jac, const double* c, double* g) {
  Eigen::Map<Eigen::Matrix<double, kT, 1>>(g).noalias() +=
      Ambient<Rows>(jac).template leftCols<kT>().transpose() * Eigen::Map<const Eigen::Matrix<double, Rows, 1>>(c);
}


// The bodies' fill-reducing elimination order: AMD on the body graph
// (bodies coupled by a constraint); body -> position.
std::vector<int> EliminationPositions(const ConstraintSet& constraints) {
  const int bodies = constraints.state_size() / kT;
  std::vector<Eigen::Triplet<double>> triplets;
  for (int b = 0; b < bodies; ++b) triplets.emplace_back(b, b, 1.0);
  for (const ConstraintBlock& block : constraints.blocks()) {
    if (block.bodies.size() > 2 || block.rows > kMaxBlockRows || block.rows < 1) {
      throw std::logic_error("SparseLevenbergMarquardt: a constraint of more than two bodies or 9 rows");
    }
    if (block.bodies.size() == 2 && block.bodies[0] != kWorld && block.bodies[1] != kWorld &&
        block.bodies[0] != block.bodies[1]) {
      triplets.emplace_back(block.bodies[0], block.bodies[1], 1.0);
      triplets.emplace_back(block.bodies[1], block.bodies[0], 1.0);
    }
  }
  Eigen::SparseMatrix<double> graph(bodies, bodies);
  graph.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;  // order.indices()[k]: k-th body eliminated
  Eigen::AMDOrdering<int> amd;
  amd(graph, order);
  std::vector<int> position(static_cast<size_t>(bodies), -1);
  for (int k = 0; k < bodies; ++k) position[static_cast<size_t>(order.indices()[k])] = k;
  return position;
}

// The pairs of positions that a constraint couples.
std::vector<std::pair<int, int>> BodyCouplings(const ConstraintSet& constraints, const std::vector<int>& position) {
  std::vector<std::pair<int, int>> couplings;
  for (const ConstraintBlock& block : constraints.blocks()) {
    if (block.bodies.size() == 2 && block.bodies[0] != kWorld && block.bodies[1] != kWorld &&
        block.bodies[0] != block.bodies[1]) {
      couplings.emplace_back(position[static_cast<size_t>(block.bodies[0])],
                             position[static_cast<size_t>(block.bodies[1])]);
    }
  }
  return couplings;
}

}  // namespace

SparseLevenbergMarquardt::SparseLevenbergMarquardt(const ConstraintSet& constraints)
    : constraints_(constraints),
      bodies_(constraints.state_size() / kT),
      position_(EliminationPositions(constraints)),
      elimination_(bodies_, BodyCouplings(constraints, position_)) {
  const std::vector<ConstraintBlock>& blocks = constraints_.blocks();
  normal_.assign(static_cast<size_t>(elimination_.num_blocks()), Block::Zero());
  factor_.assign(static_cast<size_t>(elimination_.num_blocks()), Block::Zero());

  // Each constraint's place: its Jacobian storage and its blocks.
  int offset = 0;
  for (size_t k = 0; k < blocks.size(); ++k) {
    const ConstraintBlock& block = blocks[k];
    Term term;
    term.block = static_cast<int>(k);
    term.num_params = static_cast<int>(block.bodies.size()) + (block.control_size > 0 ? 1 : 0);
    term.jacobian = offset;
    for (size_t p = 0; p < block.bodies.size(); ++p) {
      term.pos[p] = block.bodies[p] == kWorld ? -1 : position_[block.bodies[p]];
    }
    offset += static_cast<int>(block.bodies.size()) * block.rows * kA;
    if (term.pos[0] >= 0 && term.pos[1] >= 0) {
      if (term.pos[0] == term.pos[1]) {
        throw std::logic_error("SparseLevenbergMarquardt: a constraint between a body and itself");
      }
      const int i = std::max(term.pos[0], term.pos[1]), j = std::min(term.pos[0], term.pos[1]);
      term.off = elimination_.Block(i, j);
      term.off_transposed = term.pos[1] > term.pos[0];
    }
    terms_.push_back(term);
  }
  jacobians_.assign(offset, 0.0);
  C_.resize(constraints_.num_rows());
  g_.resize(kT * bodies_);
  ds_.resize(kT * bodies_);
  chord_.resize(kT * bodies_);
  trial_ = State(bodies_);
}

bool SparseLevenbergMarquardt::RigidImageConverged(const State& s, const Eigen::VectorXd& u, double converged_energy,
                                                   SparseLmSummary* summary) {
  if (!evaluated_) return false;  // no Jacobian to bound the gradient with
  const double energy = constraints_.Energy(s, u, &frames_);  // residuals only
  if (!(energy <= converged_energy)) return false;
  // |J^T C|_inf <= |J^T C|_2 <= |J|_F |C|_2, |C|_2 = sqrt(2 E). |J|_F is
  // invariant under a rigid motion of the whole mechanism, so the norm of the
  // last evaluated Jacobian (at the moved state's preimage, or within
  // rounding-level steps of it) serves; the factor 2 covers that distance.
  if (jacobian_frobenius_ < 0) {
    jacobian_frobenius_ = Eigen::Map<const Eigen::VectorXd>(jacobians_.data(), Eigen::Index(jacobians_.size())).norm();
  }
  summary->converged = true;
  summary->energy = energy;
  summary->gradient_norm = 2 * jacobian_frobenius_ * std::sqrt(2 * energy);
  summary->gradient_norm_is_bound = true;
  return true;
}

double SparseLevenbergMarquardt::Evaluate(const State& s, const Eigen::VectorXd& u) {
  evaluated_ = true;
  jacobian_frobenius_ = -1;
  const std::vector<ConstraintBlock>& blocks = constraints_.blocks();
  constraints_.ComputeFrames(s, &frames_);
  for (const Term& term : terms_) {
    const ConstraintBlock& block = blocks[term.block];
    const double* params[3];
    const BodyFrame* block_frames[2];
    double* jacobians[3] = {nullptr, nullptr, nullptr};  // none for the ground and the controls
    const int num_bodies = static_cast<int>(block.bodies.size());
    for (int p = 0; p < num_bodies; ++p) {
      params[p] = ConstraintSet::Pose(s, block.bodies[p]);
      if (term.pos[p] >= 0) jacobians[p] = jacobians_.data() + term.jacobian + p * block.rows * kA;
    }
    if (block.control_size > 0) params[num_bodies] = u.data() + block.control_offset;
    ConstraintSet::BlockFrames(block, frames_, block_frames);
    block.framed->EvaluateInFrames(block_frames, params, C_.data() + block.row, jacobians);
  }
  return 0.5 * C_.squaredNorm();
}

void SparseLevenbergMarquardt::Gradient() {
  g_.setZero();
  const std::vector<ConstraintBlock>& blocks = constraints_.blocks();
  for (const Term& term : terms_) {
    const ConstraintBlock& block = blocks[term.block];
    const double* c = C_.data() + block.row;
    for (int p = 0; p < 2; ++p) {
      if (term.pos[p] < 0) continue;
      const double* jac = jacobians_.data() + term.jacobian + p * block.rows * kA;
      double* g = g_.data() + kT * term.pos[p];
      switch (block.rows) {
        case 1: GradientTerm<1>(jac, c, g); break;
        case 2: GradientTerm<2>(jac, c, g); break;
        case 3: GradientTerm<3>(jac, c, g); break;
        case 4: GradientTerm<4>(jac, c, g); break;
        case 5: GradientTerm<5>(jac, c, g); break;
        case 6: GradientTerm<6>(jac, c, g); break;
        case 7: GradientTerm<7>(jac, c, g); break;
        case 8: GradientTerm<8>(jac, c, g); break;
        default: GradientTerm<9>(jac, c, g); break;
      }
    }
  }
}

void SparseLevenbergMarquardt::AccumulateNormal() {
  for (Block& b : normal_) b.setZero();
  const std::vector<ConstraintBlock>& blocks = constraints_.blocks();
  for (const Term& term : terms_) {
    const ConstraintBlock& block = blocks[term.block];
    const double* jac0 = term.pos[0] >= 0 ? jacobians_.data() + term.jacobian : nullptr;
    const double* jac1 = term.pos[1] >= 0 ? jacobians_.data() + term.jacobian + block.rows * kA : nullptr;
    Block* diag0 = term.pos[0] >= 0 ? &normal_[term.pos[0]] : nullptr;
    Block* diag1 = term.pos[1] >= 0 ? &normal_[term.pos[1]] : nullptr;
    Block* off = term.off >= 0 ? &normal_[term.off] : nullptr;
    switch (block.rows) {
      case 1: AccumulateTerm<1>(jac0, jac1, diag0, diag1, off, term.off_transposed); break;
      case 2: AccumulateTerm<2>(jac0, jac1, diag0, diag1, off, term.off_transposed); break;
      case 3: AccumulateTerm<3>(jac0, jac1, diag0, diag1, off, term.off_transposed); break;
      case 4: AccumulateTerm<4>(jac0, jac1, diag0, diag1, off, term.off_transposed); break;
      case 5: AccumulateTerm<5>(jac0, jac1, diag0, diag1, off, term.off_transposed); break;
      case 6: AccumulateTerm<6>(jac0, jac1, diag0, diag1, off, term.off_transposed); break;
      case 7: AccumulateTerm<7>(jac0, jac1, diag0, diag1, off, term.off_transposed); break;
      case 8: AccumulateTerm<8>(jac0, jac1, diag0, diag1, off, term.off_transposed); break;
      default: AccumulateTerm<9>(jac0, jac1, diag0, diag1, off, term.off_transposed); break;
    }
  }
}

bool SparseLevenbergMarquardt::Factorize(double mu) {
  std::copy(normal_.begin(), normal_.end(), factor_.begin());
  if (mu > 0) {
    for (int j = 0; j < bodies_; ++j) {
      factor_[j].diagonal() += mu * normal_[j].diagonal().cwiseMax(kMinDiagonal).cwiseMin(kMaxDiagonal);
    }
  }
  // Right-looking block LL^T; the diagonal slot keeps L_jj^{-1} (lower
  // triangular), so that both the column scaling and the substitutions are
  // plain fixed-size products.
  for (int j = 0; j < bodies_; ++j) {
    if (!block_kernels::InvertCholeskyFactor(&factor_[j])) return false;
    const Block inverse_transpose = factor_[j].transpose();
    for (int k = elimination_.column_begin(j); k < elimination_.column_end(j); ++k) {
      Block& L = factor_[elimination_.block(k)];
      const Block scaled = L.lazyProduct(inverse_transpose);
      L = scaled;
    }
    for (const BlockElimination::Update* up = elimination_.updates_begin(j); up != elimination_.updates_end(j); ++up) {
      factor_[up->target].noalias() -= factor_[up->a].lazyProduct(factor_[up->b].transpose());
    }
  }
  return true;
}

void SparseLevenbergMarquardt::SolveNegative(const Eigen::VectorXd& rhs, Eigen::VectorXd* x) const {
  Eigen::VectorXd& y = *x;
  y = -rhs;
  // L y = -rhs.
  for (int j = 0; j < bodies_; ++j) {
    const BlockVector yj = factor_[j].lazyProduct(y.segment<kT>(kT * j));
    y.segment<kT>(kT * j) = yj;
    for (int k = elimination_.column_begin(j); k < elimination_.column_end(j); ++k) {
      y.segment<kT>(kT * elimination_.row(k)).noalias() -= factor_[elimination_.block(k)].lazyProduct(yj);
    }
  }
  // L^T x = y.
  for (int j = bodies_ - 1; j >= 0; --j) {
    BlockVector yj = y.segment<kT>(kT * j);
    for (int k = elimination_.column_begin(j); k < elimination_.column_end(j); ++k) {
      yj.noalias() -= factor_[elimination_.block(k)].transpose().lazyProduct(y.segment<kT>(kT * elimination_.row(k)));
    }
    y.segment<kT>(kT * j).noalias() = factor_[j].transpose().lazyProduct(yj);
  }
}

void SparseLevenbergMarquardt::Plus(const State& s, const Eigen::VectorXd& ds, State* out) const {
  const PoseManifold manifold;
  for (int b = 0; b < bodies_; ++b) manifold.Plus(s.pose(b), ds.data() + kT * position_[b], out->pose(b));
}

// After an accepted Gauss-Newton step of length `step` [max-norm] that
// lowered E by `decrease`: the convergence tests, the stop on a linear rate
// and the chord step. Returns true when Solve's loop ends.
bool SparseLevenbergMarquardt::AfterAcceptedStep(State* s, const Eigen::VectorXd& u, double step, double decrease,
                                                 int max_iterations, bool stop_when_linear, double* energy,
                                                 double* last_ratio, SparseLmSummary* summary) {
  if (*energy <= kAssembledEnergyFloor || decrease <= kRelativeDecrease * (*energy + decrease)) {
    summary->converged = true;
    return true;
  }
  // The next step, estimated with this factorisation (one substitution).
  SolveNegative(g_, &chord_);
  const double next = chord_.lpNorm<Eigen::Infinity>();
  if (next <= kStepTolerance) {
    summary->converged = true;
    return true;
  }
  const double ratio = next / step;
  if (stop_when_linear && *energy > kStationaryEnergy && ratio >= kLinearContraction &&
      *last_ratio >= kLinearContraction && ratio >= *last_ratio / kRateSpread &&
      ratio <= kRateSpread * *last_ratio) {
    summary->linear = true;
    return true;
  }
  *last_ratio = ratio;
  // Taking the chord step instead of a full iteration leaves an error of
  // about rho |dc|, rho ~ kChordSafety |dc| / |ds|: when that is below
  // kStepTolerance, the chord step is the last one.
  if (kChordSafety * next * next > kStepTolerance * step || summary->iterations >= max_iterations) return false;
  ++summary->iterations;
  ++summary->chord_steps;
  Plus(*s, chord_, &trial_);
  const double chord_energy = Evaluate(trial_, u);
  if (chord_energy <= *energy) {
    *s = trial_;
    *energy = chord_energy;
    Gradient();
    summary->converged = true;
  } else if (next <= kNoiseStep) {
    summary->converged = true;  // rounding noise: *s and its gradient stay
  } else {
    *energy = Evaluate(*s, u);  // back to *s for a full iteration
    Gradient();
  }
  return summary->converged;
}

// The iteration. From the state s_k (E, g = J^T C and J^T J there):
//   ds = -(J^T J + mu D)^{-1} g, the trial s_k (+) ds evaluated (C and J);
// accepted when E decreases. Then, before J^T J is built at the new point,
// the next step is estimated with the factorisation just used and the
// gradient at the new point, dc = -(J^T J + mu D)^{-1} g_new (one
// substitution). Near a solution such a chord step leaves an error of about
// rho |dc|, rho ~ |dc| / |ds| (times at most kChordSafety); when that is
// below kStepTolerance, dc is taken as the last step (one evaluation, no
// J^T J, no factorisation), otherwise a full iteration follows. So the
// convergence stays quadratic and its last step is cheap.
//
// The same ratio |dc| / |ds| shows when the convergence is only linear
// (E > 0 at a stationary point): with `stop_when_linear` the loop then
// stops, for the caller's exact Newton steps (SparseLmSummary::linear).
//
// A reachable warm-started paper-size step (E ~ 1e-4 to start) typically
// takes two Gauss-Newton steps and one chord step and ends at rounding level
// (E ~ 1e-31), where the previous loop took three full iterations to
// E ~ 1e-26 (|dE/ds| <= 1e-14).
SparseLmSummary SparseLevenbergMarquardt::Solve(State* s, const Eigen::VectorXd& u, int max_iterations,
                                                bool stop_when_linear, double converged_energy) {
  SparseLmSummary summary;
  if (converged_energy > 0 && converged_energy <= kRigidCheckEnergy && RigidImageConverged(*s, u, converged_energy,
                                                                                             &summary)) {
    return summary;
  }
  double last_ratio = 0;  // |next step| / |step| of the last accepted Gauss-Newton step, 0 if none
  double energy = Evaluate(*s, u);
  Gradient();
  bool have_normal = false;  // J^T J at *s in normal_
  double mu = 0;
  if (energy <= std::max(kAssembledEnergyFloor, converged_energy)) summary.converged = true;
  while (!summary.converged && summary.iterations < max_iterations) {
    if (!have_normal) {
      AccumulateNormal();
      have_normal = true;
    }
    ++summary.iterations;
    if (!Factorize(mu)) {
      mu = NextDamping(mu);
      if (mu > kMaxDamping) break;
      continue;
    }
    SolveNegative(g_, &ds_);
    const double step = ds_.lpNorm<Eigen::Infinity>();
    // Converged if the step is at rounding level, or if the decrease it
    // promises (the linear model's, at least -g.ds / 2) could not be told
    // from the rounding of E (a stationary point with E > 0).
    if (step <= kStepTolerance || -0.5 * g_.dot(ds_) <= kRelativeDecrease * energy) {
      summary.converged = true;
      break;
    }
    Plus(*s, ds_, &trial_);
    const double trial_energy = Evaluate(trial_, u);
    if (!(trial_energy < energy)) {
      // Rejected: J^T J and g at *s are still in place (C_ and jacobians_
      // now hold the trial's, which nothing reads). A tiny undamped step
      // that does not lower E is rounding noise: converged.
      if (mu == 0 && step <= kNoiseStep) {
        summary.converged = true;
        break;
      }
      mu = NextDamping(mu);
      if (mu > kMaxDamping) break;
      continue;
    }
    *s = trial_;  // a copy into the same storage: the state's addresses stay (Ceres holds them)
    const double decrease = energy - trial_energy;
    energy = trial_energy;
    Gradient();
    have_normal = false;
    mu = mu / 10 < kMinDamping ? 0 : mu / 10;
    if (AfterAcceptedStep(s, u, step, decrease, max_iterations, stop_when_linear, &energy, &last_ratio, &summary)) {
      break;
    }
  }
  summary.energy = energy;
  summary.gradient_norm = g_.lpNorm<Eigen::Infinity>();
  return summary;
}

}  // namespace ccma
