#include "problems/loaded_equilibrium.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/internal/dense_factorizations.h"
#include "ccma/internal/format.h"
#include "ccma/internal/joint_deviation.h"
#include "ccma/rotation.h"
#include "problems/internal/compliant_equilibrium.h"
#include "problems/internal/loaded_newton.h"
#include "problems/internal/loaded_sparse_path.h"

namespace ccma {
namespace {

constexpr int kMaxNewtonIterations = 25;  // per load step
constexpr int kMaxRestoreSteps = 20;   // minimum-norm corrections onto the rigid rows
constexpr double kRigidRowTolerance = 1e-13;  // m (or rad-like): a rigid row that holds
constexpr double kUnheldTolerance = 1e-8;     // as analyses/compliance.cc

using Point = LoadedPoint;

// One linearisation of the loaded mechanism at a point: its linear system
// and the generalized force the springs and loads leave unbalanced.
struct Linearisation {
  std::unique_ptr<CompliantEquilibrium> system;
  Eigen::VectorXd force;  // [t Q(s); 0] - S^T k e: what moves the point (system size)
  double unbalanced = 0;  // max |force| along the motions A allows
};

// Newton's method on the equilibrium at a fraction t of the loads, and the
// load steps that carry t from 0 to 1.
class LoadedSolver {
 public:
  LoadedSolver(const Model& model, const ConstraintSet& set, const Eigen::VectorXd& u, const ExternalWrench& wrench)
      : model_(model), set_(set), u_(u), wrench_(wrench), compliant_(CompliantEquilibrium::CompliantControls(model)) {}

  const std::vector<int>& compliant() const { return compliant_; }
  Linearisation Linearise(const Point& x, double t) const;
  // Newton iterations at load fraction t from x until `tolerances` hold;
  // false (x unchanged) when they do not get there.
  bool Converge(double t, const LoadedTolerances& tolerances, int* iterations, Point* x, Linearisation* at) const;

 private:
  // Moves x back onto the rigid rows with minimum-norm corrections of
  // `projector` (a decomposition of A); false when they do not hold.
  bool Restore(const MinimumNormSolver& projector, Point* x) const;
  // The Newton step at x: the linear system's stiffness plus the preload's
  // geometric stiffness (the rigid rows' curvature weighted by their
  // multipliers, minus t dQ/ds); Gauss-Newton where that is not positive.
  Eigen::VectorXd NewtonStep(const Point& x, double t, const Linearisation& at) const;

  const Model& model_;
  const ConstraintSet& set_;
  const Eigen::VectorXd u_;
  const ExternalWrench wrench_;
  const std::vector<int> compliant_;
};

Linearisation LoadedSolver::Linearise(const Point& x, double t) const {
  Linearisation out;
  const Eigen::VectorXd u_eff = CommandedControls(u_, compliant_, x.delta);
  out.system = std::make_unique<CompliantEquilibrium>(model_, set_, x.s, u_eff);
  const CompliantEquilibrium& sys = *out.system;
  Eigen::VectorXd g, e;
  LoadedResiduals(model_, set_, x, u_eff, &g, &e);
  out.force = Eigen::VectorXd::Zero(sys.size());
  out.force.head(sys.state_size()) = t * GeneralizedLoads(model_, x.s, wrench_);
  out.force -= sys.S().transpose() * (sys.k().asDiagonal() * e);
  Eigen::VectorXd unbalanced = out.force;
  if (sys.A().rows() > 0) unbalanced += sys.A().transpose() * sys.Multipliers(Eigen::VectorXd::Zero(sys.size()), out.force);
  out.unbalanced = unbalanced.size() > 0 ? unbalanced.lpNorm<Eigen::Infinity>() : 0.0;
  return out;
}

bool LoadedSolver::Restore(const MinimumNormSolver& projector, Point* x) const {
  const int n = set_.state_size();
  Eigen::VectorXd g, e;
  double last = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kMaxRestoreSteps; ++i) {
    LoadedResiduals(model_, set_, *x, CommandedControls(u_, compliant_, x->delta), &g, &e);
    const double size = g.size() > 0 ? g.lpNorm<Eigen::Infinity>() : 0.0;
    if (size <= kRigidRowTolerance) return true;
    if (!(size < last) || i == kMaxRestoreSteps) return false;
    last = size;
    const Eigen::VectorXd y = projector.solve(-g);
    x->s.Plus(y.head(n));
    x->delta += y.tail(y.size() - n);
  }
  return false;
}

Eigen::VectorXd LoadedSolver::NewtonStep(const Point& x, double t, const Linearisation& at) const {
  const CompliantEquilibrium& sys = *at.system;
  const int n = sys.state_size();
  // mu: A^T mu = force (Multipliers solves A^T lambda = -force here).
  Eigen::VectorXd w = Eigen::VectorXd::Zero(set_.num_rows());
  if (sys.A().rows() > 0) {
    const Eigen::VectorXd mu = -sys.Multipliers(Eigen::VectorXd::Zero(sys.size()), at.force);
    for (size_t i = 0; i < sys.set_rows().size(); ++i) {
      if (sys.set_rows()[i] >= 0) w[sys.set_rows()[i]] = mu[static_cast<int>(i)];
    }
  }
  Eigen::MatrixXd extra = Eigen::MatrixXd::Zero(sys.size(), sys.size());
  Eigen::MatrixXd H_s = -t * GeneralizedLoadsJacobian(model_, x.s, wrench_);
  set_.AddWeightedHessian(x.s, CommandedControls(u_, compliant_, x.delta), w, &H_s);
  extra.topLeftCorner(n, n) = H_s;
  bool newton = false;
  return sys.Displacement(at.force, extra, &newton);
}

bool LoadedSolver::Converge(double t, const LoadedTolerances& tolerances, int* iterations, Point* x,
                            Linearisation* at) const {
  Point trial = *x;
  Linearisation here = Linearise(trial, t);
  for (int i = 0; i < kMaxNewtonIterations; ++i) {
    const CompliantEquilibrium& sys = *here.system;
    const Eigen::VectorXd y = NewtonStep(trial, t, here);
    // The step moves nothing along the motions no spring resists: it tells
    // the distance to the equilibrium only where no force acts along them.
    const double step_size = sys.IdleForce(here.force) <= tolerances.force && y.size() > 0
                                 ? y.lpNorm<Eigen::Infinity>()
                                 : std::numeric_limits<double>::infinity();
    if (tolerances.Converged(here.unbalanced, step_size)) {
      *x = std::move(trial);
      *at = std::move(here);
      return true;
    }
    ++*iterations;
    MinimumNormSolver projector;
    if (sys.A().rows() > 0) projector.setThreshold(1e-10).compute(sys.A());
    trial.s.Plus(y.head(sys.state_size()));
    trial.delta += y.tail(y.size() - sys.state_size());
    if (sys.A().rows() > 0 && !Restore(projector, &trial)) return false;
    Linearisation next = Linearise(trial, t);
    // Newton converges fast or not at all: a growing force means the load step was too large.
    if (!(next.unbalanced < 2 * here.unbalanced)) return false;
    here = std::move(next);
  }
  return false;
}

// The dense path: load steps of Newton's method with minimum-norm
// restoration (LoadedSolver), from the rigid assembly. Fills converged,
// load_fraction, unbalanced, held and message; leaves the point in *x.
void SolveLoadedDense(const Model& model, const ConstraintSet& set, const State& rigid, const Eigen::VectorXd& u,
                      const ExternalWrench& wrench, const LoadedTolerances& tolerances, const LoadedOptions& options,
                      Point* x, LoadedEquilibrium* out) {
  const LoadedSolver solver(model, set, u, wrench);
  *x = Point{rigid, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(solver.compliant().size()))};
  // Load steps: the whole load first; a step whose Newton iterations fail is
  // quartered, a step that succeeds lets the next one double.
  Linearisation at = solver.Linearise(*x, 0.0);
  double t = 0, dt = 1;
  while (t < 1 && dt >= kMinLoadStep && out->iterations < options.max_iterations) {
    const double next = std::min(1.0, t + dt);
    const bool ok = solver.Converge(next, tolerances, &out->iterations, x, &at);
    if (ok) {
      t = next;
      dt *= 2;
    } else {
      dt /= 4;
    }
  }
  out->load_fraction = t;
  if (t < 1) at = solver.Linearise(*x, 1.0);
  out->converged = t >= 1;
  out->unbalanced = at.unbalanced;
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(6, at.system->size());  // the end-effector's motion over [ds; delta]
  G.leftCols(model.state_size()) = EndEffectorJacobian(model, x->s);
  out->held = at.system->UnheldMotion(ControlledRows(model, G)) <= kUnheldTolerance;
  if (!out->converged) {
    out->message = !out->held ? "the loaded mechanism is not held: a motion that no spring resists moves the end-effector"
                              : "no equilibrium found: the springs held " + FormatG(100 * t, 3) +
                                    "% of the loads and no more in " + std::to_string(out->iterations) +
                                    " Newton iterations (past a limit load the mechanism gives way), leaving " +
                                    FormatG(at.unbalanced) + " N or N*m unbalanced";
  }
}

// Whether every motion no spring resists leaves the end-effector's controlled
// components in place at x.
bool Held(const Model& model, const ConstraintSet& set, const Eigen::VectorXd& u, const Point& x) {
  const std::vector<int> compliant = CompliantEquilibrium::CompliantControls(model);
  const CompliantEquilibrium system(model, set, x.s, CommandedControls(u, compliant, x.delta),
                                    CompliantEquilibrium::Factorization::kIdleMotions);
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(6, system.size());
  G.leftCols(model.state_size()) = EndEffectorJacobian(model, x.s);
  return system.UnheldMotion(ControlledRows(model, G)) <= kUnheldTolerance;
}

// Why the sparse path's equilibrium was not found.
std::string NotConvergedMessage(const SparsePathResult& r, const LoadedEquilibrium& out) {
  if (!out.held) return "the loaded mechanism is not held: a motion that no spring resists moves the end-effector";
  const std::string held = "the springs held " + FormatG(100 * r.load_fraction, 3) + "% of the loads";
  if (r.stalled) {
    return "no equilibrium found: " + held + " and no more (a load step of " + FormatG(100 * kMinLoadStep) +
           "% failed beyond it: past a limit load the mechanism gives way)";
  }
  return "no equilibrium found within " + std::to_string(r.iterations) + " Newton iterations: " + held +
         ", and the load steps were still advancing (a soft mechanism under large loads; LoadedOptions::max_iterations)";
}

// A model without stiffness: its rigid assembly, converged.
LoadedEquilibrium RigidEquilibrium(const Model& model, const State& rigid) {
  LoadedEquilibrium out;
  out.converged = true;
  out.state = rigid;
  out.yields = Eigen::VectorXd::Zero(model.num_controls());
  return out;
}

}  // namespace

void DescribeLoadedPoint(const Model& model, const State& rigid, const LoadedPoint& x, const std::vector<int>& compliant,
                         LoadedEquilibrium* out) {
  out->state = x.s;
  out->yields = Eigen::VectorXd::Zero(model.num_controls());
  for (size_t i = 0; i < compliant.size(); ++i) out->yields[compliant[i]] = x.delta[static_cast<int>(i)];
  const EndEffectorPose before = ComputeEndEffectorPose(model, rigid), after = ComputeEndEffectorPose(model, x.s);
  out->deflection.head<3>() = after.position - before.position;
  out->deflection.tail<3>() = QuaternionLog(Eigen::Quaterniond(after.rotation * before.rotation.transpose()));
  out->max_body_m = 0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    out->max_body_m = std::max(out->max_body_m, (x.s.p_WB(b) - rigid.p_WB(b)).norm());
  }
}

std::shared_ptr<LoadedWorkspace> NewLoadedWorkspace() { return std::make_shared<LoadedWorkspace>(); }

LoadedEquilibrium SolveLoadedEquilibrium(const Model& model, const State& rigid, const Eigen::VectorXd& u,
                                         const ExternalWrench& wrench, const LoadedOptions& options) {
  if (!model.compliant()) return RigidEquilibrium(model, rigid);
  return SolveLoadedEquilibrium(model, ConstraintSet(model), rigid, u, wrench, options);
}

LoadedEquilibrium SolveLoadedEquilibrium(const Model& model, const ConstraintSet& set, const State& rigid,
                                         const Eigen::VectorXd& u, const ExternalWrench& wrench,
                                         const LoadedOptions& options) {
  if (!model.compliant()) return RigidEquilibrium(model, rigid);
  LoadedEquilibrium out;
  Point x;
  if (!options.sparse) {
    SolveLoadedDense(model, set, rigid, u, wrench, LoadedTolerancesFor(model, rigid, wrench, options.force_tolerance),
                     options, &x, &out);
  } else {
    const std::shared_ptr<LoadedWorkspace> workspace = options.workspace ? options.workspace : NewLoadedWorkspace();
    SparsePathResult r = SolveLoadedSparsePath(model, set, rigid, u, wrench, options, workspace.get());
    x = std::move(r.x);
    out.converged = r.converged;
    out.iterations = r.iterations;
    out.unbalanced = r.unbalanced;
    out.load_fraction = r.load_fraction;
    // Not converged, or a motion no spring resists moves the end-effector.
    if (!r.converged || options.check_held) out.held = Held(model, set, u, x);
    if (!out.held) out.converged = false;
    if (!out.converged) out.message = NotConvergedMessage(r, out);
  }
  DescribeLoadedPoint(model, rigid, x, CompliantEquilibrium::CompliantControls(model), &out);
  return out;
}

void DecideHeld(const Model& model, const Eigen::VectorXd& u, LoadedEquilibrium* loaded) {
  if (model.compliant()) DecideHeld(model, ConstraintSet(model), u, loaded);
}

void DecideHeld(const Model& model, const ConstraintSet& set, const Eigen::VectorXd& u, LoadedEquilibrium* loaded) {
  if (!model.compliant()) return;
  const std::vector<int> compliant = CompliantEquilibrium::CompliantControls(model);
  Point x{loaded->state, Eigen::VectorXd(static_cast<Eigen::Index>(compliant.size()))};
  for (size_t i = 0; i < compliant.size(); ++i) x.delta[static_cast<Eigen::Index>(i)] = loaded->yields[compliant[i]];
  loaded->held = Held(model, set, u, x);
}

}  // namespace ccma
