// The cost of compliance in statics (docs/statics.md, "Compliance"):
// ComputeStatics on a generated 48-agent CCMA (and the 6-agent one) as a
// rigid model, then with every base compliant (stiffness [2e4, 2e4, 500]) and
// every revolute joint's rotations as springs (2e3 N*m/rad), gravity on a
// 2 kg payload. The target: compliant within 2x of rigid.
//   build/benchmarks/statics_benchmark --benchmark_repetitions=5 \
//       --benchmark_report_aggregates_only=true
#include <string>

#include <benchmark/benchmark.h>

#include "ccma/ccma.h"

namespace {

using namespace ccma;

Model Generated(int agents, bool compliant) {
  StewartOptions options;
  options.agents = agents;
  options.base_radius = agents > 6 ? 3.0 : options.base_radius;
  Model model = LoadModelFromString(GenerateStewartModel(options), "generated.yaml");
  model.end_effector.payload.mass = 2.0;
  if (!compliant) return model;
  for (MobileBase& base : model.mobile_bases) base.stiffness.k = Eigen::Vector3d(2e4, 2e4, 500);
  for (Joint& joint : model.joints) {
    if (joint.type == JointType::kRevolute) joint.stiffness.rotation = {2e3, 2e3};
  }
  return model;
}

void BM_Statics(benchmark::State& state, int agents, bool compliant) {
  const Model model = Generated(agents, compliant);
  ForwardProblem forward(model);
  if (!forward.Solve(model.home_controls()).assembled) {
    state.SkipWithError("not assembled at home");
    return;
  }
  for (auto _ : state) {
    const StaticsReport r = ComputeStatics(model, forward.state(), forward.controls());
    benchmark::DoNotOptimize(r.actuators.data());
  }
  state.counters["state_size"] = model.state_size();
}

BENCHMARK_CAPTURE(BM_Statics, agents6_rigid, 6, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Statics, agents6_compliant, 6, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Statics, agents48_rigid, 48, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Statics, agents48_compliant, 48, true)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
