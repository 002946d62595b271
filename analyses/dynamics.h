// Inverse dynamics of a closed-loop mechanism along a timed path of its
// controls (cli.md, `ccma dynamics`; docs/dynamics.md).
//
// Method. The controls are a natural cubic spline in time through the rows
// (problems/natural_spline.h), which gives u, u', u'' at every row. The
// configuration is assembled at u (ForwardProblem, row after row, so it
// follows one branch); the bodies' velocities and accelerations follow from
// the controls' to second order through the constraints' exact derivatives
// (problems/internal/control_motion.h: q' = S u', q'' = S u'' + S'(u', u')).
// Efforts: Newton-Euler with the constraint multipliers (d'Alembert). The
// inertia of every mass becomes a load (ccma/inertial_loads.h) beside
// gravity, the payload and the wrench, and the constraints hold the sum
// exactly as in statics: the same EffortEvaluator (analyses/statics.h), so at
// rest (u' = u'' = 0) the efforts are statics' to the last bit, indeterminate
// models get statics' minimum-norm answer, and compliant models share the
// loads through their springs as statics does (the springs' own vibration is
// not modelled). Why not the projected equations: the multipliers also give
// every joint's force, and one code path cannot disagree with statics.
//
// Units: s, N, N*m, J, W; controls in m or rad.
#ifndef CCMA_ANALYSES_DYNAMICS_H_
#define CCMA_ANALYSES_DYNAMICS_H_

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "analyses/statics.h"
#include "ccma/loads.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// A timed path of the controls, as a trajectory CSV holds it.
struct ControlPath {
  std::string source;                      // file name, for messages
  std::vector<double> times;               // s, strictly increasing, at least 2 rows
  std::vector<Eigen::VectorXd> controls;   // per row, Model::num_controls()
  std::vector<int> lines;                  // per row, its line in `source` (0: unknown)
  // Per row, the end-effector point the file says was reached (x_m, y_m,
  // z_m), when it says: a row assembled elsewhere is another model's path.
  std::vector<std::optional<Eigen::Vector3d>> reached;
};

// The motion of every body and the efforts at one instant.
struct DynamicsPoint {
  StaticsReport efforts;         // control_efforts, actuators, limits (EffortEvaluator::AtLoads)
  Eigen::VectorXd velocity;      // state tangent: per body [omega; v] (inertial_loads.h)
  Eigen::VectorXd acceleration;  // per body [alpha; a]
  double kinetic = 0;            // J
  double potential = 0;          // J
  double power = 0;              // efforts . u' [W]
  double rate_inconsistency = 0; // ControlMotion::Inconsistency
};

// The per-instant kernel, the model's constraint set built once.
class InverseDynamics {
 public:
  explicit InverseDynamics(const Model& model);  // keeps a reference to `model`
  ~InverseDynamics();
  // At the assembled configuration (s, u) moving with control rates du and
  // accelerations ddu (num_controls each), under gravity, the payload and
  // `wrench`. Throws std::invalid_argument past kMaxStaticsEntries.
  DynamicsPoint At(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& du, const Eigen::VectorXd& ddu,
                   const ExternalWrench& wrench = {}) const;

 private:
  const Model& model_;
  std::unique_ptr<const ConstraintSet> set_;
  std::unique_ptr<const HessianSolver> symbolic_;  // of set_, copied by every row's factorisation
  EffortEvaluator efforts_;
};

struct DynamicsRow {
  double time = 0;             // s
  bool assembled = false;
  double residual_energy = 0;  // m^2
  Eigen::VectorXd rates;       // u' (num_controls)
  Eigen::VectorXd efforts;     // num_controls; empty when not assembled
  double kinetic = 0, potential = 0, power = 0;
  bool within_limits = true;
};

// One control over the path (cli.md `actuators`).
struct ActuatorSummary {
  std::string name;   // the base's or the joint's
  std::string kind;   // "base_<control>" (x, y, theta; legged: heading, height, roll, pitch) or "joint"
  double peak_effort = 0;   // the signed effort of largest magnitude
  double peak_time = 0;     // s
  double rms_effort = 0;    // sqrt(integral e^2 dt / duration), trapezoid
  std::optional<std::pair<double, double>> limit;  // [lo, hi]; a base's x, y: [-push_limit, push_limit]
  double peak_rate = 0;     // the signed rate u' of largest magnitude [m/s or rad/s]
  // velocity_limit on this control: a joint's; a base's V on |(x', y')| for
  // x and y, W on theta' (legged: Vz, Wr, Wp on height', roll', pitch').
  std::optional<double> rate_limit;
  // At every assembled row: the effort (a base's push: |(e_x, e_y)| <=
  // push_limit) and the rate (a base's |(x', y')| <= V).
  bool within_limits = true;
};

struct DynamicsReport {
  std::vector<DynamicsRow> rows;
  std::vector<ActuatorSummary> actuators;  // control order
  double duration = 0;       // s
  bool assembled = true;     // every row
  int not_assembled_rows = 0;
  bool within_limits = true;
  std::vector<std::string> limiting;  // names, once each, in control order
  double energy = 0;         // the trapezoid of power over the rows [J]
  double max_power = 0;      // W
  double max_rate_inconsistency = 0;  // max over rows of ControlMotion::Inconsistency
};

// The controls with every base heading (theta, heading) unwrapped along the
// rows, so that a spline does not turn a base the long way round where the
// file wrapped an angle to (-pi, pi].
std::vector<Eigen::VectorXd> UnwrappedControls(const Model& model, std::vector<Eigen::VectorXd> controls);

// Throws std::invalid_argument naming the path's source and line when the
// row's reached point (if the file gives one) is more than 1e-6 m from the
// end-effector assembled at `s`: a trajectory of another model.
void CheckReachedPoint(const Model& model, const State& s, const ControlPath& path, size_t row);

// Inverse dynamics at every row of `path`. Throws std::invalid_argument
// naming source and line when the path is not this model's (a row's reached
// point more than 1e-6 m from the assembled end-effector) or too large
// (kMaxStaticsEntries).
DynamicsReport ComputeDynamics(const Model& model, const ControlPath& path, const ExternalWrench& wrench = {});

}  // namespace ccma

#endif  // CCMA_ANALYSES_DYNAMICS_H_
