#include "problems/internal/loaded_newton.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "ccma/internal/joint_deviation.h"
#include "problems/internal/kkt_factorization.h"
#include "problems/internal/kkt_newton_step.h"
#include "problems/internal/loaded_kkt.h"

namespace ccma {
namespace {

constexpr int kMaxChords = 8;  // chord steps in a row before a full one

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

LoadedKkt& LoadedWorkspace::SystemFor(const Model& model, const ConstraintSet& set) {
  if (!system || !system->Fits(model, set)) {
    system = std::make_unique<LoadedKkt>(model, set);
    w.resize(0);
    mu.resize(0);
  }
  return *system;
}

LoadedNewtonResult SolveLoadedNewton(const Model& model, const ConstraintSet& set, const Eigen::VectorXd& u,
                                     const ExternalWrench& wrench, const LoadedTolerances& tolerances, int max_iterations,
                                     LoadedWorkspace* workspace, LoadedPoint* x) {
  LoadedNewtonResult out;
  LoadedKkt& system = workspace->SystemFor(model, set);
  LoadedPoint trial = *x;
  // The rigid rows' multipliers in set order (w) and in A's (mu_last), which
  // weigh their curvature in the Newton matrix: the last equilibrium's of
  // this workspace when there is one (a nearby one carries nearly the same
  // preload, so the first step is nearly Newton's), else none.
  Eigen::VectorXd w = workspace->w.size() == set.num_rows() ? workspace->w : Eigen::VectorXd::Zero(set.num_rows());
  Eigen::VectorXd mu_last = workspace->mu.size() == system.rigid_rows() ? workspace->mu : Eigen::VectorXd();
  const int n = system.state_size(), N = system.size(), m = system.rigid_rows();
  double last_merit = std::numeric_limits<double>::infinity(), last_size = last_merit, last_unbalanced = last_merit;
  int full_steps = 0, chords = 0;
  bool full = true;
  for (int i = 0; i <= max_iterations; ++i) {
    const bool chord = !full && mu_last.size() == m;
    AssembleStep(model, set, chord, trial, u, wrench, w, mu_last, &system);
    Eigen::VectorXd z;
    if (!SolveKktAt(system, !chord, mu_last, &workspace->kkt, &z)) return out;
    const Eigen::VectorXd mu = z.tail(m);
    const double unbalanced = UnbalancedAt(system, chord, chord ? mu_last : mu);
    const double row_size = system.g().size() > 0 ? system.g().lpNorm<Eigen::Infinity>() : 0.0;
    const double step_size = z.head(N).lpNorm<Eigen::Infinity>();
    out.unbalanced = unbalanced;
    if (row_size <= kKktRowTolerance && tolerances.Converged(unbalanced, step_size)) {
      out.converged = true;
      *x = std::move(trial);
      workspace->KeepMultipliers(chord ? mu_last : mu);
      return out;
    }
    if (!chord) {
      // Newton converges fast or not at all: a growing imbalance hands over
      // (to load steps, then to the dense path).
      const double merit = unbalanced / tolerances.force + row_size / kKktRowTolerance;
      if (full_steps++ >= 2 && !(merit < 2 * last_merit)) return out;
      last_merit = merit;
      chords = 0;
      ++out.iterations;
    }
    if (i == max_iterations) break;
    // A step this long crosses a motion nothing resists (eps_H alone holds
    // it: the mechanism is not held) or a limit load: the dense path decides.
    if (!(step_size <= kKktMaxStep)) return out;
    trial.s.Plus(z.head(n));
    trial.delta += z.segment(n, N - n);
    mu_last = mu;
    if (!chord) w = system.SetOrder(mu);
    // Chord steps (the last factorisation against the residuals at the new
    // point) while they and the unbalanced force shrink tenfold: they correct what a soft motion
    // stretches of the stiff springs to second order, which limits a full
    // step's reach on a mechanism whose springs span many orders of
    // magnitude; a full step where they stall.
    full = ++chords > kMaxChords || !(step_size < 0.1 * last_size) || !(unbalanced < 0.1 * last_unbalanced);
    last_size = step_size;
    last_unbalanced = unbalanced;
  }
  return out;
}

}  // namespace ccma
