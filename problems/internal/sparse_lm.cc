#include "problems/internal/sparse_lm.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ccma {
namespace {

constexpr int kMaxBlockRows = 9;           // the largest cost function (cost_functions/)
constexpr double kInitialDamping = 1e-8;   // warm starts are near-Newton steps (Ceres: radius 1e8)
constexpr double kMinDamping = 1e-16;
constexpr double kMaxDamping = 1e16;
// Marquardt's scaling D = diag(J^T J), clamped as Ceres clamps it.
constexpr double kMinDiagonal = 1e-6;
constexpr double kMaxDiagonal = 1e32;
// Stop when max |dE/ds| is below this: ~ roundoff of J^T C for reachable
// controls (E ~ 1e-30), so that the state is exact to ~1e-14 m or rad.
constexpr double kGradientTolerance = 1e-14;

// The value index of entry (row, col) of a compressed column-major matrix.
int EntryIndex(const Eigen::SparseMatrix<double>& m, int row, int col) {
  const int* begin = m.innerIndexPtr() + m.outerIndexPtr()[col];
  const int* end = m.innerIndexPtr() + m.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  return static_cast<int>(it - m.innerIndexPtr());
}

}  // namespace

SparseLevenbergMarquardt::SparseLevenbergMarquardt(const ConstraintSet& constraints)
    : constraints_(constraints), n_(constraints.state_size()) {
  const int bodies = n_ / kPoseTangentSize;
  // The pattern: every body's diagonal block, and both off-diagonal blocks of
  // every pair of bodies a constraint couples.
  std::vector<Eigen::Triplet<double>> triplets;
  auto add_block = [&triplets](int a, int b) {
    for (int i = 0; i < kPoseTangentSize; ++i) {
      for (int j = 0; j < kPoseTangentSize; ++j) {
        triplets.emplace_back(kPoseTangentSize * a + i, kPoseTangentSize * b + j, 0.0);
      }
    }
  };
  for (int b = 0; b < bodies; ++b) add_block(b, b);
  for (const ConstraintBlock& block : constraints_.blocks()) {
    for (int p : block.bodies) {
      for (int q : block.bodies) {
        if (p != kWorld && q != kWorld && p != q) add_block(p, q);
      }
    }
  }
  jtj_.resize(n_, n_);
  jtj_.setFromTriplets(triplets.begin(), triplets.end());
  jtj_.makeCompressed();
  damped_ = jtj_;
  diagonal_.resize(n_);
  for (int i = 0; i < n_; ++i) diagonal_[i] = EntryIndex(jtj_, i, i);

  // Where each block's J_p^T J_q lands, and its Jacobian storage.
  int offset = 0;
  for (const ConstraintBlock& block : constraints_.blocks()) {
    if (block.bodies.size() > 2 || block.rows > kMaxBlockRows) {
      throw std::logic_error("SparseLevenbergMarquardt: a constraint of more than two bodies or 9 rows");
    }
    jacobian_offset_.push_back(offset);
    const int params = static_cast<int>(block.bodies.size()) + (block.control_size > 0 ? 1 : 0);
    offset += params * kMaxBlockRows * kPoseAmbientSize;
    std::vector<int> entries;
    for (int p : block.bodies) {
      for (int q : block.bodies) {
        if (p == kWorld || q == kWorld) continue;
        for (int i = 0; i < kPoseTangentSize; ++i) {
          for (int j = 0; j < kPoseTangentSize; ++j) {
            entries.push_back(EntryIndex(jtj_, kPoseTangentSize * p + i, kPoseTangentSize * q + j));
          }
        }
      }
    }
    pair_entries_.push_back(std::move(entries));
  }
  jacobians_.assign(offset, 0.0);

  // The fill-reducing order P (AMD) of the pattern, applied once to the
  // pattern itself: damped_ holds P A P^T's upper triangle. Which entry of
  // jtj_ lands where is found by permuting a matrix of entry numbers.
  Eigen::AMDOrdering<int> amd;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
  amd(jtj_, inverse);
  permutation_ = inverse.inverse();
  Eigen::SparseMatrix<double> numbers = jtj_;
  for (int k = 0; k < numbers.nonZeros(); ++k) numbers.valuePtr()[k] = k + 1;
  damped_.resize(n_, n_);
  damped_.selfadjointView<Eigen::Upper>() = numbers.selfadjointView<Eigen::Lower>().twistedBy(permutation_);
  damped_.makeCompressed();
  permuted_entry_.assign(jtj_.nonZeros(), -1);
  for (int k = 0; k < damped_.nonZeros(); ++k) {
    permuted_entry_[static_cast<int>(damped_.valuePtr()[k]) - 1] = k;  // only lower entries of jtj_ map
  }
  permuted_diagonal_.resize(n_);
  for (int i = 0; i < n_; ++i) permuted_diagonal_[i] = permuted_entry_[diagonal_[i]];
  ldlt_.analyzePattern(damped_);  // symbolic factorisation, once
  saved_jtj_.resize(jtj_.nonZeros());
  permuted_g_.resize(n_);
  permuted_ds_.resize(n_);
  C_.resize(constraints_.num_rows());
  g_.resize(n_);
  ds_.resize(n_);
  trial_ = State(bodies);
}

double SparseLevenbergMarquardt::Linearize(const State& s, const Eigen::VectorXd& u) {
  std::fill(jtj_.valuePtr(), jtj_.valuePtr() + jtj_.nonZeros(), 0.0);
  g_.setZero();
  const std::vector<ConstraintBlock>& blocks = constraints_.blocks();
  using Jacobian = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, kPoseAmbientSize, Eigen::RowMajor>>;
  for (size_t k = 0; k < blocks.size(); ++k) {
    const ConstraintBlock& block = blocks[k];
    const double* params[3];
    double* jacobians[3];
    const int num_bodies = static_cast<int>(block.bodies.size());
    for (int p = 0; p < num_bodies; ++p) params[p] = ConstraintSet::Pose(s, block.bodies[p]);
    if (block.control_size > 0) params[num_bodies] = u.data() + block.control_offset;
    const int params_count = num_bodies + (block.control_size > 0 ? 1 : 0);
    for (int p = 0; p < params_count; ++p) {
      jacobians[p] = jacobians_.data() + jacobian_offset_[k] + p * kMaxBlockRows * kPoseAmbientSize;
    }
    double* c = C_.data() + block.row;
    block.cost->Evaluate(params, c, jacobians);
    const Eigen::Map<const Eigen::VectorXd> residual(c, block.rows);
    // J_p^T C into g, and J_p^T J_q into the pattern (tangent: the left 6
    // columns). Copied into fixed 9-row matrices, zero below the block's
    // rows: fixed-size products are unrolled and vectorised (a dynamic row
    // count made them ten times slower).
    using Tangent = Eigen::Matrix<double, kMaxBlockRows, kPoseTangentSize>;
    Tangent J[2];
    Eigen::Matrix<double, kMaxBlockRows, 1> r = Eigen::Matrix<double, kMaxBlockRows, 1>::Zero();
    r.head(block.rows) = residual;
    for (int p = 0; p < num_bodies; ++p) {
      J[p].setZero();
      J[p].topRows(block.rows) = Jacobian(jacobians[p], block.rows, kPoseAmbientSize).leftCols<kPoseTangentSize>();
    }
    const int* entry = pair_entries_[k].data();
    double* values = jtj_.valuePtr();
    for (int p = 0; p < num_bodies; ++p) {
      if (block.bodies[p] == kWorld) continue;
      g_.segment<kPoseTangentSize>(kPoseTangentSize * block.bodies[p]).noalias() += J[p].transpose().lazyProduct(r);
      for (int q = 0; q < num_bodies; ++q) {
        if (block.bodies[q] == kWorld) continue;
        Eigen::Matrix<double, kPoseTangentSize, kPoseTangentSize, Eigen::RowMajor> M;
        M.noalias() = J[p].transpose().lazyProduct(J[q]);
        for (int e = 0; e < kPoseTangentSize * kPoseTangentSize; ++e) values[entry[e]] += M.data()[e];
        entry += kPoseTangentSize * kPoseTangentSize;
      }
    }
  }
  return 0.5 * C_.squaredNorm();
}

void SparseLevenbergMarquardt::Damp(double mu) {
  double* out = damped_.valuePtr();
  std::fill(out, out + damped_.nonZeros(), 0.0);
  const double* in = jtj_.valuePtr();
  for (size_t k = 0; k < permuted_entry_.size(); ++k) {
    if (permuted_entry_[k] >= 0) out[permuted_entry_[k]] += in[k];
  }
  // Marquardt: + mu diag(J^T J), the diagonal clamped.
  for (int i = 0; i < n_; ++i) out[permuted_diagonal_[i]] += mu * std::clamp(in[diagonal_[i]], kMinDiagonal, kMaxDiagonal);
}

SparseLmSummary SparseLevenbergMarquardt::Solve(State* s, const Eigen::VectorXd& u, int max_iterations) {
  SparseLmSummary summary;
  double energy = Linearize(*s, u);
  double mu = kInitialDamping;
  while (summary.iterations < max_iterations) {
    summary.gradient_norm = g_.lpNorm<Eigen::Infinity>();
    if (summary.gradient_norm <= kGradientTolerance || energy == 0) {
      summary.converged = true;
      break;
    }
    // (J^T J + mu D) ds = -J^T C, D = diag(J^T J) clamped; solved as
    // (P M P^T) (P ds) = -P g.
    ++summary.iterations;
    Damp(mu);
    ldlt_.factorize(damped_);
    if (ldlt_.info() != Eigen::Success) {
      mu = std::min(mu * 10, kMaxDamping);
      continue;
    }
    permuted_g_.noalias() = permutation_ * g_;
    permuted_ds_ = ldlt_.solve(permuted_g_);
    ds_.noalias() = permutation_.transpose() * permuted_ds_;
    ds_ = -ds_;
    trial_ = *s;  // same size: no allocation
    trial_.Plus(ds_);
    // Linearise at the trial point: its E decides, and its derivatives are
    // the next iteration's when accepted; otherwise the saved ones return.
    std::copy(jtj_.valuePtr(), jtj_.valuePtr() + jtj_.nonZeros(), saved_jtj_.begin());
    saved_C_ = C_;
    saved_g_ = g_;
    const double trial_energy = Linearize(trial_, u);
    if (trial_energy < energy) {
      *s = trial_;  // a copy into the same storage: the state's addresses stay (Ceres holds them)
      const double decrease = energy - trial_energy;
      const bool small_step = ds_.lpNorm<Eigen::Infinity>() <= 1e-15;
      energy = trial_energy;
      mu = std::max(mu / 10, kMinDamping);
      if (decrease <= 1e-15 * (energy + decrease) || small_step) {
        summary.converged = true;
        summary.gradient_norm = g_.lpNorm<Eigen::Infinity>();
        break;
      }
    } else {
      std::copy(saved_jtj_.begin(), saved_jtj_.end(), jtj_.valuePtr());
      C_ = saved_C_;
      g_ = saved_g_;
      if (ds_.lpNorm<Eigen::Infinity>() <= 1e-15 || mu >= kMaxDamping) {
        summary.converged = ds_.lpNorm<Eigen::Infinity>() <= 1e-15;
        break;
      }
      mu = std::min(mu * 10, kMaxDamping);
    }
  }
  summary.energy = energy;
  return summary;
}

}  // namespace ccma
