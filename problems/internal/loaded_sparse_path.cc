#include "problems/internal/loaded_sparse_path.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "problems/internal/compliant_equilibrium.h"
#include "problems/internal/loaded_newton.h"
#include "problems/internal/loaded_tolerances.h"

namespace ccma {
namespace {

constexpr int kMaxNewtonPerLoad = 15;  // factorisations per attempt

// The model and wrench at a fraction t of the loads: gravity (so every mass
// and the payload) and the wrench scaled by t.
Model AtLoadFraction(const Model& model, double t) {
  Model scaled = model;
  scaled.gravity *= t;
  return scaled;
}
ExternalWrench AtLoadFraction(const ExternalWrench& wrench, double t) {
  ExternalWrench scaled = wrench;
  scaled.force *= t;
  scaled.moment *= t;
  return scaled;
}

// The start points at the whole load: the warm start when it fits, then the
// rigid assembly (compliant: the model's compliant controls).
std::vector<LoadedPoint> Starts(const Model& model, const State& rigid, const LoadedOptions& options,
                                const std::vector<int>& compliant) {
  std::vector<LoadedPoint> starts;
  if (options.start_state && options.start_state->num_bodies() == rigid.num_bodies() &&
      options.start_yields.size() == model.num_controls()) {
    LoadedPoint warm{*options.start_state, Eigen::VectorXd(static_cast<Eigen::Index>(compliant.size()))};
    for (size_t i = 0; i < compliant.size(); ++i) warm.delta[static_cast<Eigen::Index>(i)] = options.start_yields[compliant[i]];
    starts.push_back(std::move(warm));
  }
  starts.push_back(LoadedPoint{rigid, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(compliant.size()))});
  return starts;
}

// Newton at a fraction t of the loads from *x (left there on success).
LoadedNewtonResult NewtonAt(const Model& model, const ConstraintSet& set, const State& rigid, const Eigen::VectorXd& u,
                            const ExternalWrench& wrench, double t, const LoadedOptions& options, int budget,
                            LoadedWorkspace* workspace, LoadedPoint* x) {
  const Model scaled = t == 1 ? Model() : AtLoadFraction(model, t);
  const Model& at = t == 1 ? model : scaled;
  const ExternalWrench w = AtLoadFraction(wrench, t);
  return SolveLoadedNewton(at, set, u, w, LoadedTolerancesFor(at, rigid, w, options.force_tolerance),
                           std::min(kMaxNewtonPerLoad, budget), workspace, x);
}

}  // namespace

SparsePathResult SolveLoadedSparsePath(const Model& model, const ConstraintSet& set, const State& rigid,
                                       const Eigen::VectorXd& u, const ExternalWrench& wrench,
                                       const LoadedOptions& options, LoadedWorkspace* workspace) {
  const std::vector<int> compliant = CompliantEquilibrium::CompliantControls(model);
  SparsePathResult out;
  for (LoadedPoint& start : Starts(model, rigid, options, compliant)) {
    const LoadedNewtonResult r = NewtonAt(model, set, rigid, u, wrench, 1.0, options,
                                          options.max_iterations - out.iterations, workspace, &start);
    out.iterations += std::max(1, r.iterations);
    if (!r.converged) continue;
    out.converged = true;
    out.load_fraction = 1;
    out.unbalanced = r.unbalanced;
    out.x = std::move(start);
    return out;
  }
  out.x = LoadedPoint{rigid, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(compliant.size()))};
  double dt = 0.25;
  while (out.load_fraction < 1 && dt >= kMinLoadStep && out.iterations < options.max_iterations) {
    const double next = std::min(1.0, out.load_fraction + dt);
    LoadedPoint trial = out.x;
    const LoadedNewtonResult r = NewtonAt(model, set, rigid, u, wrench, next, options,
                                          options.max_iterations - out.iterations, workspace, &trial);
    out.iterations += std::max(1, r.iterations);
    if (r.converged) {
      out.x = std::move(trial);
      out.load_fraction = next;
      out.unbalanced = r.unbalanced;
      dt *= 2;
    } else {
      dt /= 4;
    }
  }
  out.converged = out.load_fraction >= 1;
  out.stalled = !out.converged && dt < kMinLoadStep;
  return out;
}

}  // namespace ccma
