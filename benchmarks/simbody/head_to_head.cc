#include "benchmarks/simbody/head_to_head.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Simbody.h>

#include "benchmarks/simbody/circle_track.h"
#include "benchmarks/simbody/simbody_mechanism.h"
#include "problems/forward_problem.h"

namespace ccma::simbody_benchmark {
namespace {

using Clock = std::chrono::steady_clock;

double MicrosecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

// System::projectQ(state, accuracy) as Simbody spells it out
// (SimTKcommon/Simulation/src/System.cpp), with the options it does not
// expose: the infinity norm (every constraint <= tolerance, not their RMS)
// and no exception (a failed step is counted, not fatal).
class Projector {
 public:
  Projector(const SimTK::MultibodySystem& system, double tolerance) : system_(system), options_(tolerance) {
    options_.setOption(SimTK::ProjectOptions::UseInfinityNorm);
    options_.setOption(SimTK::ProjectOptions::DontThrow);
  }
  // Moves the prescribed bases to time t and projects the free q's.
  void Project(SimTK::State* state, double t) {
    state->setTime(t);
    system_.realize(*state, SimTK::Stage::Time);
    system_.prescribeQ(*state);
    system_.realize(*state, SimTK::Stage::Position);
    system_.projectQ(*state, no_error_estimate_, options_, results_);
  }
  const SimTK::ProjectResults& results() const { return results_; }
  bool succeeded() const { return results_.getExitStatus() == SimTK::ProjectResults::Succeeded; }

 private:
  const SimTK::MultibodySystem& system_;
  SimTK::ProjectOptions options_;
  SimTK::ProjectResults results_;
  SimTK::Vector no_error_estimate_;  // empty: no integrator error estimate to project
};

}  // namespace

HeadToHeadResult RunHeadToHead(const Model& model, const HeadToHeadOptions& options) {
  const CircleTrack track = MakeCircleTrack(model, options.plane, options.steps, options.radius_m);
  const SimbodyMechanism mechanism(model, std::make_shared<const std::vector<Eigen::VectorXd>>(track.controls));
  const SimTK::MultibodySystem& system = mechanism.system();

  HeadToHeadResult result;
  result.model = model.name;
  result.path = CirclePlaneName(options.plane);
  result.steps = track.steps();
  result.laps = options.laps;
  result.tolerance = options.tolerance;
  result.ccma_state_size = model.state_size();
  result.ccma_constraint_rows = model.num_constraints();
  result.simbody_tree_joints = mechanism.num_tree_joints();
  result.simbody_loop_joints = mechanism.num_loop_joints();
  result.simbody_constraint_equations = mechanism.num_constraint_equations();

  // Every solver starts assembled at home (time 0 = controls[0]), untimed.
  SimTK::State projected = mechanism.HomeState();
  Projector projector(system, options.tolerance);
  projector.Project(&projected, 0);

  SimTK::Assembler assembler(system);
  // The error tolerance decides success (infinity norm by default). With
  // only constraints and no goals the Assembler hands the problem to its
  // interior-point optimiser (Ipopt), which also gets the accuracy as its
  // convergence tolerance; set to the tolerance too. (Measured: any accuracy
  // from 1e-12 to 0.5 gives the same iterations and times on these paths.)
  assembler.setErrorTolerance(options.tolerance);
  assembler.setAccuracy(options.tolerance);
  SimTK::State assembler_start = mechanism.HomeState();
  int still_redundant = 0;
  result.assembler_disabled_equations = mechanism.DisableRedundantAngleConstraints(&assembler_start, &still_redundant);
  // Dependent equations left (whole Ball or Weld rows, e.g. 4dof_complete):
  // Ipopt would refuse every step, so the Assembler is not run at all.
  result.assembler_run = still_redundant == 0;
  if (!result.assembler_run) {
    result.assembler_note = std::to_string(still_redundant) +
                            " dependent equations remain beyond ConstantAngle ones; Ipopt needs independent ones";
  } else {
    assembler.initialize(assembler_start);
    assembler.assemble();
  }
  // Mobilities (u), not q: a Ball keeps 4 q slots even in the Assembler's
  // Euler-angle mode. The bases' 3 each are prescribed.
  result.simbody_free_mobilities = projected.getNU() - model.num_base_controls();

  ForwardProblem forward(model);
  ForwardOptions no_predictor_options;
  no_predictor_options.secant_predictor = false;
  no_predictor_options.rigid_motion_predictor = false;
  ForwardProblem forward_no_predictor(model, no_predictor_options);
  forward.Solve(track.controls[0]);
  forward_no_predictor.Solve(track.controls[0]);

  // One step of each solver to the track's step k, timed alone with
  // steady_clock, into the given samples.
  const auto run_ccma = [&](int k, StepSamples* samples) {
    const Clock::time_point start = Clock::now();
    const ForwardResult r = forward.Solve(track.controls[k]);
    samples->Add(MicrosecondsSince(start), r.iterations);
    samples->failures += !r.assembled;
    result.worst_residual_ccma = std::max(result.worst_residual_ccma, std::sqrt(2 * r.residual_energy));
  };
  const auto run_ccma_no_predictor = [&](int k, StepSamples* samples) {
    const Clock::time_point start = Clock::now();
    const ForwardResult r_np = forward_no_predictor.Solve(track.controls[k]);
    samples->Add(MicrosecondsSince(start), r_np.iterations);
    samples->failures += !r_np.assembled;
  };
  // Simbody's time is the step index (base_track_motion.h).
  const auto run_project_q = [&](int k, StepSamples* samples) {
    const Clock::time_point start = Clock::now();
    projector.Project(&projected, k);
    samples->Add(MicrosecondsSince(start), projector.results().getNumIterations());
    samples->failures += !projector.succeeded();
    result.worst_error_project_q = std::max(result.worst_error_project_q, projector.results().getNormOnExit());
  };
  const auto run_track = [&](int k, StepSamples* samples) {
    if (!result.assembler_run) return;
    // Iterations of the interior-point optimiser: one constraint Jacobian each.
    const int jacobians_before = assembler.getNumErrorJacobianEvals();
    const Clock::time_point start = Clock::now();
    bool tracked = true;
    try {
      assembler.track(k);
    } catch (const std::exception&) {
      tracked = false;  // TrackFailed: the tolerance was not reached
    }
    samples->Add(MicrosecondsSince(start), assembler.getNumErrorJacobianEvals() - jacobians_before);
    samples->failures += !tracked;
    result.worst_error_track = std::max(result.worst_error_track, assembler.calcCurrentErrorNorm());
  };

  for (int lap = 0; lap < options.laps; ++lap) {
    for (int k = 1; k <= track.steps(); ++k) {
      // The four solvers in turn, the first one rotating from step to step:
      // whichever runs first finds the caches filled by another library's
      // code and data, so no solver is always first (or always right after
      // its twin).
      const std::array<std::function<void()>, 4> solvers = {
          [&] { run_ccma(k, &result.ccma); }, [&] { run_ccma_no_predictor(k, &result.ccma_no_predictor); },
          [&] { run_project_q(k, &result.project_q); }, [&] { run_track(k, &result.assembler_track); }};
      for (int j = 0; j < 4; ++j) solvers[(k + j) % 4]();

      const Eigen::Vector3d p_WE_ccma = forward.end_effector().position;
      result.max_ee_error_ccma_m = std::max(result.max_ee_error_ccma_m, (p_WE_ccma - track.p_WE_target[k]).norm());
      result.max_ee_difference_project_q_m = std::max(
          result.max_ee_difference_project_q_m, (mechanism.EndEffectorPosition(projected) - p_WE_ccma).norm());
      if (result.assembler_run) {
        result.max_ee_difference_track_m =
            std::max(result.max_ee_difference_track_m,
                     (mechanism.EndEffectorPosition(assembler.getInternalState()) - p_WE_ccma).norm());
      }
    }
  }

  // Then each solver alone, all laps in its own loop from where it stopped
  // (the track is closed): its code and data stay in the caches, as in a
  // program that runs one solver. Same tracks, same tolerances.
  for (int lap = 0; lap < options.laps; ++lap) {
    for (int k = 1; k <= track.steps(); ++k) run_ccma(k, &result.ccma_alone);
  }
  for (int lap = 0; lap < options.laps; ++lap) {
    for (int k = 1; k <= track.steps(); ++k) run_project_q(k, &result.project_q_alone);
  }
  for (int lap = 0; lap < options.laps; ++lap) {
    for (int k = 1; k <= track.steps(); ++k) run_track(k, &result.assembler_track_alone);
  }
  // All three back at the track's start: they must still agree.
  const Eigen::Vector3d p_WE_ccma = forward.end_effector().position;
  result.max_ee_difference_project_q_m =
      std::max(result.max_ee_difference_project_q_m, (mechanism.EndEffectorPosition(projected) - p_WE_ccma).norm());
  if (result.assembler_run) {
    result.max_ee_difference_track_m = std::max(
        result.max_ee_difference_track_m, (mechanism.EndEffectorPosition(assembler.getInternalState()) - p_WE_ccma).norm());
  }
  return result;
}

}  // namespace ccma::simbody_benchmark
