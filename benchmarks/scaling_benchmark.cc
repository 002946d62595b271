// How the solvers scale with the number of agents (issue: work bounded by
// what it costs), on generated models:
//   ControlStep/{wheeled,legged}/N: one control step (the end-effector moved
//     the paper's step, alternating with the way back) on a generated CCMA
//     with N omni bases (3 controls each) and on N quadrupeds under one
//     platform (6 controls each). Target: legged at most 3x wheeled at N = 1000.
//   Statics/N and Loaded/N: ComputeStatics (linear compliance, dense) against
//     the nonlinear loaded equilibrium (sparse Newton, `held` decided) on a
//     generated CCMA with stiffness on every joint and base and 1 kg per body
//     under a 1 N push. Target: the loaded equilibrium grows no faster.
//   build/benchmarks/scaling_benchmark --benchmark_repetitions=3 \
//       --benchmark_report_aggregates_only=true
#include <string>

#include <benchmark/benchmark.h>

#include "benchmarks/paper_step.h"
#include "ccma/ccma.h"

namespace {

using namespace ccma;

Model GeneratedModel(const std::string& kind, int agents) {
  if (kind == "legged") {
    LeggedOptions options;
    options.agents = agents;
    return LoadModelFromString(GenerateLeggedModel(options), "legged.yaml");
  }
  StewartOptions options;
  options.agents = agents;
  return LoadModelFromString(GenerateStewartModel(options), "wheeled.yaml");
}

void BM_ControlStep(benchmark::State& state, const std::string& kind, int agents) {
  const Model model = GeneratedModel(kind, agents);
  ControlProblem control(model);
  const double reached_fraction = TimePaperStepsOutAndBack(state, &control);
  state.counters["controls"] = static_cast<double>(control.effective_controls().size());
  state.counters["reached_fraction"] = reached_fraction;
}

Model CompliantEverywhere(int agents) {
  Model model = GeneratedModel("wheeled", agents);
  for (MobileBase& base : model.mobile_bases) base.stiffness.k = Eigen::Vector3d(1e5, 1e5, 1e3);
  for (Body& body : model.bodies) body.inertia.mass = 1.0;
  for (Joint& joint : model.joints) {
    joint.stiffness.translation.assign(static_cast<size_t>(TranslationSpringCount(joint.type)), 1e7);
    joint.stiffness.rotation.assign(static_cast<size_t>(RotationSpringCount(joint.type)), 1e4);
  }
  return model;
}

void BM_Compliant(benchmark::State& state, int agents, bool loaded) {
  const Model model = CompliantEverywhere(agents);
  ForwardProblem forward(model);
  if (!forward.Solve(model.home_controls()).assembled) {
    state.SkipWithError("not assembled at home");
    return;
  }
  ExternalWrench push;
  push.force = Eigen::Vector3d(0, 0, -1);
  long converged = 0, runs = 0;
  for (auto _ : state) {
    if (loaded) {
      converged += SolveLoadedEquilibrium(model, forward.state(), forward.controls(), push).converged;
    } else {
      converged += ComputeStatics(model, forward.state(), forward.controls(), push).balanced;
    }
    ++runs;
  }
  state.counters["converged_fraction"] = double(converged) / runs;
  state.counters["state_size"] = model.state_size();
}

int Register() {
  for (const int agents : {10, 20, 35, 60, 100, 1000}) {
    for (const std::string kind : {"wheeled", "legged"}) {
      benchmark::RegisterBenchmark(("ControlStep/" + kind + "/" + std::to_string(agents)).c_str(), BM_ControlStep, kind,
                                   agents)
          ->Unit(benchmark::kMillisecond);
    }
  }
  for (const int agents : {5, 10, 20, 40, 80}) {
    benchmark::RegisterBenchmark(("Statics/" + std::to_string(agents)).c_str(), BM_Compliant, agents, false)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Loaded/" + std::to_string(agents)).c_str(), BM_Compliant, agents, true)
        ->Unit(benchmark::kMillisecond);
  }
  return 0;
}
const int kRegistered = Register();

}  // namespace

BENCHMARK_MAIN();
