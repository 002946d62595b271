// The cost of compensating the deflection (docs/statics.md, "Control that
// compensates"): a control step (the end-effector moved 1 cm and 0.01 rad
// from home, the mechanism assembled again at home before each) on the
// generated 6-agent CCMA with compliant bases ([2e4, 2e4, 500]) and
// revolute rotations (2e3 N*m/rad) carrying a 2 kg payload, plain
// (ControlProblem::MoveTo) and compensated (MoveToCompensated: a MoveTo,
// then Newton's method on the loaded equilibrium and the controls together,
// and `held` decided), also as one step of a compensated path
// (from the previous step's controls, its aim correction and loaded
// equilibrium carried over: the step from the compensated home); and the loaded
// equilibrium alone, sparse (the default) and dense. The target:
// compensated within 2x of plain.
//   build/benchmarks/compensated_control_benchmark --benchmark_repetitions=5 \
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "ccma/ccma.h"

namespace {

using namespace ccma;

Model CompliantSixAgents() {
  StewartOptions options;
  options.agents = 6;
  Model model = LoadModelFromString(GenerateStewartModel(options), "generated.yaml");
  model.end_effector.payload.mass = 2.0;
  for (MobileBase& base : model.mobile_bases) base.stiffness.k = Eigen::Vector3d(2e4, 2e4, 500);
  for (Joint& joint : model.joints) {
    if (joint.type == JointType::kRevolute) joint.stiffness.rotation = {2e3, 2e3};
  }
  return model;
}

// How a step is compensated: not at all, as `ccma control --compensate`
// (held decided at the end), or as a step of `ccma trajectory --compensate`
// (the previous step's aim correction carried over, held not decided).
enum class Compensation { kNone, kControl, kPathStep };

void BM_ControlStep(benchmark::State& state, Compensation compensation) {
  const Model model = CompliantSixAgents();
  ControlProblem control(model);
  PoseTarget target = control.CurrentPose();
  target.position += Eigen::Vector3d(0.01, 0, 0);
  target.rpy += Eigen::Vector3d(0, 0, 0.01);
  CompensationOptions options;
  Eigen::VectorXd start = model.home_controls();  // each repetition starts here
  if (compensation == Compensation::kPathStep) {
    // The correction a path's previous step leaves: the one at home.
    const PoseTarget home = control.CurrentPose();
    const CompensatedResult at_home = MoveToCompensated(&control, home);
    if (!at_home.converged) state.SkipWithError(at_home.warning.c_str());
    options.aim_offset << at_home.aim.position - home.position, at_home.aim.rpy - home.rpy;
    options.start = at_home.loaded;
    start = control.controls();  // the previous step's: its loaded equilibrium is options.start
    options.check_held = false;
    options.workspace = NewLoadedWorkspace();  // as the path's (analysed at its first step)
    MoveToCompensated(&control, target, {}, options);
  }
  int rounds = 0;
  for (auto _ : state) {
    state.PauseTiming();
    control.SetControls(start);
    state.ResumeTiming();
    if (compensation != Compensation::kNone) {
      const CompensatedResult r = MoveToCompensated(&control, target, {}, options);
      if (!r.converged) state.SkipWithError(r.warning.c_str());
      rounds = r.rounds;
    } else {
      const ControlResult r = control.MoveTo(target);
      if (!r.converged) state.SkipWithError(r.warning.c_str());
    }
  }
  state.counters["rounds"] = rounds;
}

void BM_LoadedEquilibrium(benchmark::State& state, bool sparse) {
  const Model model = CompliantSixAgents();
  ForwardProblem forward(model);
  if (!forward.Solve(model.home_controls()).assembled) state.SkipWithError("not assembled at home");
  int iterations = 0;
  for (auto _ : state) {
    LoadedOptions options;
    options.sparse = sparse;
    options.check_held = false;  // (the dense path decides it anyway)
    const LoadedEquilibrium r = SolveLoadedEquilibrium(model, forward.state(), forward.controls(), {}, options);
    iterations = r.iterations;
  }
  state.counters["iterations"] = iterations;
}

BENCHMARK_CAPTURE(BM_ControlStep, plain, Compensation::kNone)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ControlStep, compensated, Compensation::kControl)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ControlStep, compensated_path_step, Compensation::kPathStep)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LoadedEquilibrium, sparse, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LoadedEquilibrium, dense, false)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
