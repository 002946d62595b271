// The nonlinear loaded equilibrium of a compliant mechanism (cli.md,
// `ccma simulate --loaded`): where the mechanism settles under gravity, the
// payload and an external wrench when its springs (model_format.md,
// "Compliance") yield, the controls held as commanded.
//
// Unknowns: the state s and one yield delta per compliant control (its motor
// rows hold C(s, u + delta) = 0). The rigid rows hold exactly, as in the
// linear system (problems/internal/compliant_equilibrium.h); every spring
// stretches by its deviation e (a control's delta; a joint's
// ccma/internal/joint_deviation.h) and pulls with k e along its direction.
// Equilibrium: the loads Q(s) (ccma/loads.h, taken in the deflected
// configuration) plus the springs' forces -S^T k e do no work along any
// motion the rigid rows allow.
//
// Method (problems/internal/loaded_sparse_path.h): Newton's method on the
// sparse KKT system at the full loads (problems/internal/loaded_newton.h,
// each full step followed by chord steps on its factorisation), from
// LoadedOptions::start_state when given and then from the rigid assembly;
// where neither converges (a soft mechanism whose linear first step
// overshoots, a load near what the springs can carry), in load steps from
// the rigid assembly. Past a limit load where the mechanism gives way, or
// when the iterations run out, converged = false with the fraction of the
// loads held and a message saying which. `held` is decided at the point
// reached (one dense decomposition of the idle motions). The dense path
// (LoadedOptions::sparse = false: Newton's method on the linear compliant
// system plus the preload's geometric stiffness, restored onto the rigid
// rows by minimum-norm corrections, in load steps) is kept for comparison.
// The loads are re-evaluated in the deflected configuration. Small loads
// give the linear answer; large ones the exact equilibrium.
// Units: m, rad, N, N*m.
#ifndef CCMA_PROBLEMS_LOADED_EQUILIBRIUM_H_
#define CCMA_PROBLEMS_LOADED_EQUILIBRIUM_H_

#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "ccma/loads.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

class ConstraintSet;  // internal (ccma/internal/constraint_set.h)

// What the sparse path keeps between equilibria of one model (the symbolic
// analysis of its KKT factorisation): a compensated control's rounds and a
// path's steps share one, so that only the first analyses. Reusable with
// another model (it analyses again); one per thread.
class LoadedWorkspace;
std::shared_ptr<LoadedWorkspace> NewLoadedWorkspace();

struct LoadedOptions {
  int max_iterations = 200;  // KKT factorisations (the dense path: Newton iterations)
  // Converged when the rigid rows hold and the unbalanced force along the
  // allowed motions is below force_tolerance * (1 + the largest load)
  // [N or N*m], or the Newton step there is below 1e-13 m (or rad) per metre
  // of the model's size (rounding: problems/internal/loaded_tolerances.h).
  double force_tolerance = 1e-10;
  // Start from this configuration (a nearby loaded equilibrium, e.g. a
  // previous control round's) instead of the rigid assembly: its state and
  // its yields per control (LoadedEquilibrium::yields, num_controls).
  // Ignored when the sizes do not fit.
  std::optional<State> start_state;
  Eigen::VectorXd start_yields;
  // Decide `held` (one dense decomposition); false leaves it true unless the
  // dense path ran (a control round's loaded equilibrium, whose report does
  // not need it).
  bool check_held = true;
  // false: the dense path alone (the tests compare the two paths; O(N^3) a
  // Newton iteration).
  bool sparse = true;
  // Shared between calls when given (NewLoadedWorkspace); else each call
  // makes its own. Results do not depend on it.
  std::shared_ptr<LoadedWorkspace> workspace;
};

struct LoadedEquilibrium {
  bool converged = false;
  // Every motion no spring resists leaves the end-effector in place (else
  // the loads move it freely and there is no equilibrium).
  bool held = true;
  int iterations = 0;
  double unbalanced = 0;  // the largest unbalanced generalized force left [N or N*m]
  // The fraction of the loads held in equilibrium (1 when converged; the
  // reported configuration is that equilibrium's).
  double load_fraction = 1;
  State state;            // the deflected configuration
  // Per control: how far its spring let it yield (0 for a rigid control) [m or rad].
  Eigen::VectorXd yields;
  // The end-effector's displacement [m] and rotation vector [rad], world
  // frame, from the rigid assembly to the loaded one.
  Eigen::Matrix<double, 6, 1> deflection = Eigen::Matrix<double, 6, 1>::Zero();
  double max_body_m = 0;  // the largest displacement of a body frame's origin [m]
  std::string message;    // why it did not converge (empty when it did)
};

// The loaded equilibrium from the rigid assembly `rigid` at the controls u.
// A model without stiffness is its rigid assembly (converged, nothing
// yields). Throws std::invalid_argument when the dense system would exceed
// kMaxStaticsEntries doubles (ccma/limits.h).
LoadedEquilibrium SolveLoadedEquilibrium(const Model& model, const State& rigid, const Eigen::VectorXd& u,
                                         const ExternalWrench& wrench = {}, const LoadedOptions& options = {});
// The same with the model's constraint set, which a caller solving many
// equilibria of one model has already (ForwardProblem::constraints()).
LoadedEquilibrium SolveLoadedEquilibrium(const Model& model, const ConstraintSet& set, const State& rigid,
                                         const Eigen::VectorXd& u, const ExternalWrench& wrench = {},
                                         const LoadedOptions& options = {});

// Decides loaded->held at its configuration (one dense decomposition), for
// an equilibrium solved with check_held = false; u as given to the solve.
void DecideHeld(const Model& model, const Eigen::VectorXd& u, LoadedEquilibrium* loaded);
void DecideHeld(const Model& model, const ConstraintSet& set, const Eigen::VectorXd& u, LoadedEquilibrium* loaded);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_LOADED_EQUILIBRIUM_H_
