#include "problems/internal/loaded_newton.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/SparseCore>

#include "ccma/internal/joint_deviation.h"
#include "ccma/internal/joint_spring_directions.h"
#include "ccma/internal/pose_manifold.h"
#include "problems/internal/compliant_equilibrium.h"
#include "problems/internal/kkt_factorization.h"

namespace ccma {
namespace {

constexpr double kKktRowTolerance = 1e-13;  // as the dense path
// eps_H relative to the stiffest spring: idle motions move by a rounding
// force over it (1e-13 N over 1e-2 N/m), the Newton steps change by 1e-6 of a
// spring's stiffness (the iteration's rate, not its fixed point).
constexpr double kKktIdleStiffness = 1e-6;
// eps_A against the rigid rows' O(1) entries, refined away.
constexpr double kKktRowRegularization = 1e-10;
constexpr int kKktRefinements = 4;
// A refined KKT solution's residual must be within this of max(1, |rhs|)
// (N or m): the LU's is about 1e-15 of it, the LDL^T's without pivoting
// 1e-14 after refinement here; a worse one falls back to the LU. Refinement
// stops early at a hundredth of it.
constexpr double kKktResidual = 1e-12;
constexpr double kKktTightResidual = 1e-2;
constexpr double kKktMaxStep = 0.5;  // m or rad per Newton step

using KktSparse = Eigen::SparseMatrix<double>;
using KktTriplets = std::vector<Eigen::Triplet<double>>;

void AddDenseEntries(const Eigen::MatrixXd& M, Eigen::Index row0, Eigen::Index col0, KktTriplets* t) {
  for (Eigen::Index j = 0; j < M.cols(); ++j) {
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
      if (M(i, j) != 0) t->emplace_back(row0 + i, col0 + j, M(i, j));
    }
  }
}

void AddSparseEntries(const KktSparse& M, Eigen::Index row0, Eigen::Index col0, bool transposed, KktTriplets* t) {
  for (int col = 0; col < M.outerSize(); ++col) {
    for (KktSparse::InnerIterator it(M, col); it; ++it) {
      if (transposed) {
        t->emplace_back(row0 + it.col(), col0 + it.row(), it.value());  // M(i, j) at (row0 + j, col0 + i)
      } else {
        t->emplace_back(row0 + it.row(), col0 + it.col(), it.value());
      }
    }
  }
}

// d/ds of sum_r lambda_r D_r(s) over the rows of one compliant joint's
// directions (ccma/internal/joint_spring_directions.h: D = de/ds): the
// curvature of its deviations weighted by what each row carries (k e on a
// spring, the multiplier on a rigid direction), which the Newton matrix
// needs once the springs are stretched. Central differences of the
// analytic directions over the joint's two bodies (12 coordinates): it only
// shapes the iteration (its rate), never the equilibrium it converges to.
void AddJointCurvature(const Joint& joint, const State& s, const Eigen::Matrix<double, 6, 1>& lambda, int rows,
                       Eigen::MatrixXd* extra) {
  constexpr double kStep = 1e-6;  // rad or m
  const int bodies[2] = {joint.body_a, joint.body_b};
  const PoseManifold manifold;
  State at = s;  // only the perturbed body's pose changes, and is put back
  for (int side = 0; side < 2; ++side) {
    if (bodies[side] == kWorld) continue;
    double* pose = at.pose(bodies[side]);
    const Eigen::Matrix<double, kPoseAmbientSize, 1> original = Eigen::Map<const Eigen::Matrix<double, kPoseAmbientSize, 1>>(pose);
    for (int k = 0; k < 6; ++k) {
      Eigen::Matrix<double, 12, 1> g[2];
      for (int sign = 0; sign < 2; ++sign) {
        double delta[6] = {0, 0, 0, 0, 0, 0};
        delta[k] = sign == 0 ? kStep : -kStep;
        manifold.Plus(original.data(), delta, pose);
        const SpringDirections d = JointSpringDirections(joint, at);
        g[sign] = d.D.topRows(rows).transpose() * lambda.head(rows);
      }
      std::copy(original.data(), original.data() + kPoseAmbientSize, pose);
      const Eigen::Matrix<double, 12, 1> column = (g[0] - g[1]) / (2 * kStep);
      for (int other = 0; other < 2; ++other) {
        if (bodies[other] == kWorld) continue;
        extra->block<6, 1>(6 * bodies[other], 6 * bodies[side] + k) += column.segment<6>(6 * other);
      }
    }
  }
}

// AddJointCurvature for every joint with springs: lambda from the springs'
// forces k e (S's rows) and the multipliers mu of its rigid directions (A's).
void AddSpringCurvature(const Model& model, const CompliantEquilibrium& sys, const State& s, const Eigen::VectorXd& e,
                        const Eigen::VectorXd& mu, Eigen::MatrixXd* extra) {
  for (size_t j = 0; j < model.joints.size(); ++j) {
    const Joint& joint = model.joints[j];
    if (!joint.stiffness.has_springs()) continue;
    const CompliantJointRows& r = sys.joint_rows()[j];
    const int rows = TranslationSpringCount(joint.type) + RotationSpringCount(joint.type);
    Eigen::Matrix<double, 6, 1> lambda = Eigen::Matrix<double, 6, 1>::Zero();
    int a = r.a_row, spring = r.s_row;
    for (int i = 0; i < rows; ++i) {
      const bool translation = i < TranslationSpringCount(joint.type);
      const bool is_spring = !(translation ? joint.stiffness.translation : joint.stiffness.rotation).empty();
      lambda[i] = is_spring ? sys.k()[spring] * e[spring] : (mu.size() > a ? mu[a] : 0.0);
      (is_spring ? spring : a)++;
    }
    AddJointCurvature(joint, s, lambda, rows, extra);
  }
}

// The linearisation at one point: what moves it and the KKT solve.
class KktNewtonStep {
 public:
  // eps_H [N/m or N*m/rad].
  KktNewtonStep(const CompliantEquilibrium& sys, const Eigen::MatrixXd& extra_s, const Eigen::VectorXd& force,
             const Eigen::VectorXd& g, double eps_H)
      : N_(sys.size()), m_(static_cast<Eigen::Index>(sys.A().rows())) {
    A_ = sys.A().sparseView();
    const KktSparse S = sys.S().sparseView();
    const KktSparse KS = sys.k().asDiagonal() * S;
    const KktSparse H = S.transpose() * KS;
    KktTriplets t;
    t.reserve(static_cast<size_t>(H.nonZeros() + 2 * A_.nonZeros() + N_ + m_) + static_cast<size_t>(extra_s.size()) / 4);
    AddSparseEntries(H, 0, 0, false, &t);
    AddDenseEntries(extra_s, 0, 0, &t);
    AddSparseEntries(A_, N_, 0, false, &t);
    AddSparseEntries(A_, 0, N_, true, &t);
    for (Eigen::Index i = 0; i < N_; ++i) t.emplace_back(i, i, eps_H);
    eps_A_ = kKktRowRegularization;
    for (Eigen::Index i = 0; i < m_; ++i) t.emplace_back(N_ + i, N_ + i, -eps_A_);
    K_.resize(N_ + m_, N_ + m_);
    K_.setFromTriplets(t.begin(), t.end());
    rhs_.resize(N_ + m_);
    rhs_.head(N_) = force;
    rhs_.tail(m_) = -g;
    force_ = force;
  }

  // [y; mu], refined against eps_A = 0, by `kkt` (which keeps its
  // analysis from the previous steps): by its LDL^T, or its LU when the
  // LDL^T's refined solution leaves more than kKktResidual; false when
  // both fail.
  bool Solve(KktFactorization* kkt, Eigen::VectorXd* z) const {
    if (!kkt->Factorize(K_)) return false;
    if (SolveRefined(*kkt, z)) return true;
    return !kkt->uses_lu() && kkt->UseLu() && SolveRefined(*kkt, z);
  }

  // max |force - A^T mu|: what the multipliers leave unbalanced.
  double Unbalanced(const Eigen::VectorXd& mu) const {
    const Eigen::VectorXd r = force_ - A_.transpose() * mu;
    return r.size() > 0 ? r.lpNorm<Eigen::Infinity>() : 0.0;
  }

 private:
  // z from kkt's factor with up to kKktRefinements steps of iterative
  // refinement against K_ without eps_A; true when the residual is within
  // kKktResidual of |rhs|.
  bool SolveRefined(const KktFactorization& kkt, Eigen::VectorXd* z) const {
    *z = kkt.Solve(rhs_);
    const double target = kKktResidual * std::max(1.0, rhs_.lpNorm<Eigen::Infinity>());
    double size = std::numeric_limits<double>::infinity();
    for (int r = 0; r <= kKktRefinements && z->allFinite(); ++r) {
      Eigen::VectorXd residual = rhs_ - K_ * *z;
      residual.tail(m_) -= eps_A_ * z->tail(m_);
      const double next = residual.lpNorm<Eigen::Infinity>();
      if (!(next < size)) break;  // refinement has stopped gaining
      size = next;
      if (r == kKktRefinements || size <= kKktTightResidual * target) break;
      *z += kkt.Solve(residual);
    }
    return z->allFinite() && size <= target;
  }

  Eigen::Index N_, m_;
  double eps_A_ = 0;
  KktSparse A_, K_;
  Eigen::VectorXd rhs_, force_;
};

// A's multipliers mu in the constraint set's row order (0 on the rows A
// does not have: a compliant joint's springs).
Eigen::VectorXd SetOrder(const CompliantEquilibrium& sys, const Eigen::VectorXd& mu, int set_rows) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(set_rows);
  for (size_t r = 0; r < sys.set_rows().size(); ++r) {
    if (sys.set_rows()[r] >= 0) w[sys.set_rows()[r]] = mu[static_cast<Eigen::Index>(r)];
  }
  return w;
}

}  // namespace

Eigen::VectorXd CommandedControls(const Eigen::VectorXd& u, const std::vector<int>& compliant,
                                  const Eigen::VectorXd& delta) {
  Eigen::VectorXd u_eff = u;
  for (size_t i = 0; i < compliant.size(); ++i) u_eff[compliant[i]] += delta[static_cast<int>(i)];
  return u_eff;
}

void LoadedResiduals(const Model& model, const ConstraintSet& set, const LoadedPoint& x, const Eigen::VectorXd& u_eff,
                     Eigen::VectorXd* g, Eigen::VectorXd* e) {
  Eigen::VectorXd C;
  set.Evaluate(x.s, u_eff, &C);
  std::vector<double> rigid, stretch(x.delta.data(), x.delta.data() + x.delta.size());
  const auto add_block = [&](const ConstraintBlock& block) {
    for (int r = 0; r < block.rows; ++r) rigid.push_back(C[block.row + r]);
  };
  size_t b = 0;
  for (const Joint& joint : model.joints) {
    if (!joint.stiffness.has_springs()) {
      add_block(set.blocks()[b]);
    } else {
      const Eigen::VectorXd d = JointDeviation(joint, x.s);
      const int translations = TranslationSpringCount(joint.type);
      for (int i = 0; i < d.size(); ++i) {
        const bool spring = !(i < translations ? joint.stiffness.translation : joint.stiffness.rotation).empty();
        (spring ? stretch : rigid).push_back(d[i]);
      }
    }
    ++b;
    if (joint.actuated) add_block(set.blocks()[b++]);
  }
  for (; b < set.blocks().size(); ++b) add_block(set.blocks()[b]);
  *g = Eigen::Map<const Eigen::VectorXd>(rigid.data(), static_cast<Eigen::Index>(rigid.size()));
  *e = Eigen::Map<const Eigen::VectorXd>(stretch.data(), static_cast<Eigen::Index>(stretch.size()));
}

LoadedNewtonResult SolveLoadedNewton(const Model& model, const ConstraintSet& set, const Eigen::VectorXd& u,
                                     const ExternalWrench& wrench, double force_tolerance, int max_iterations,
                                     LoadedWorkspace* workspace, LoadedPoint* x) {
  LoadedNewtonResult out;
  const std::vector<int> compliant = CompliantEquilibrium::CompliantControls(model);
  LoadedPoint trial = *x;
  // The rigid rows' multipliers in set order (w) and in A's (mu_last), which
  // weigh their curvature in the Newton matrix: the last equilibrium's of
  // this workspace when they fit (a nearby one carries nearly the same
  // preload, so the first step is nearly Newton's), else none.
  Eigen::VectorXd w = workspace->w.size() == set.num_rows() ? workspace->w : Eigen::VectorXd::Zero(set.num_rows());
  Eigen::VectorXd mu_last;
  double last = std::numeric_limits<double>::infinity();
  KktFactorization& kkt = workspace->kkt;
  for (int i = 0; i <= max_iterations; ++i) {
    const Eigen::VectorXd u_eff = CommandedControls(u, compliant, trial.delta);
    const CompliantEquilibrium sys(model, set, trial.s, u_eff, CompliantEquilibrium::Factorization::kNone);
    const int n = sys.state_size();
    if (i == 0 && workspace->mu.size() == sys.A().rows() && workspace->w.size() == set.num_rows()) mu_last = workspace->mu;
    Eigen::VectorXd g, e;
    LoadedResiduals(model, set, trial, u_eff, &g, &e);
    Eigen::VectorXd force = -sys.S().transpose() * (sys.k().asDiagonal() * e);
    force.head(n) += GeneralizedLoads(model, trial.s, wrench);
    Eigen::MatrixXd extra = -GeneralizedLoadsJacobian(model, trial.s, wrench);
    set.AddWeightedHessian(trial.s, u_eff, w, &extra);
    AddSpringCurvature(model, sys, trial.s, e, mu_last, &extra);
    const double stiffest = sys.k().size() > 0 ? sys.k().maxCoeff() : 1.0;
    KktNewtonStep step(sys, extra, force, g, kKktIdleStiffness * std::max(1.0, stiffest));
    Eigen::VectorXd z;
    if (!step.Solve(&kkt, &z)) return out;
    const Eigen::VectorXd mu = z.tail(z.size() - sys.size());
    const double unbalanced = step.Unbalanced(mu);
    const double row_size = g.size() > 0 ? g.lpNorm<Eigen::Infinity>() : 0.0;
    out.unbalanced = unbalanced;
    if (unbalanced <= force_tolerance && row_size <= kKktRowTolerance) {
      out.converged = true;
      *x = std::move(trial);
      workspace->mu = mu;
      workspace->w = SetOrder(sys, mu, set.num_rows());
      return out;
    }
    // Newton converges fast or not at all: a growing imbalance hands over to the dense path.
    const double merit = unbalanced / force_tolerance + row_size / kKktRowTolerance;
    if (i >= 2 && !(merit < 2 * last)) return out;
    last = merit;
    if (i == max_iterations) break;
    // A step this long crosses a motion nothing resists (eps_H alone holds
    // it: the mechanism is not held) or a limit load: the dense path decides.
    if (!(z.head(sys.size()).lpNorm<Eigen::Infinity>() <= kKktMaxStep)) return out;
    ++out.iterations;
    trial.s.Plus(z.head(n));
    trial.delta += z.segment(n, sys.size() - n);
    mu_last = mu;
    w = SetOrder(sys, mu, set.num_rows());
  }
  return out;
}

}  // namespace ccma
