// The dense rank decisions (ccma::RankRevealingDecomposition) against Eigen's
// BDCSVD, which they replaced (tests/data/rank_decisions/README.md), on the
// matrices the three sites give them: each site is run once on a model with
// SetRankDecisionObserver capturing its matrix, then the decompositions are
// timed on that matrix:
//   moved_components   [dC/ds, dC/du_eff] (an import's controlled components)
//   idle_motions       [dC/ds; dX/ds]     (CompareConfigurations, branches)
//   compliant          S Z                (the compliant equilibrium's springs)
// For each: "bdcsvd" (Eigen::BDCSVD, V in full, as before), "jacobi"
// (kJacobiSvd) and "qr" (kPivotedQr).
//   build/benchmarks/rank_decision_benchmark --benchmark_repetitions=5 \
//       --benchmark_report_aggregates_only=true
#include <iostream>
#include <string>
#include <vector>

#include <Eigen/SVD>
#include <benchmark/benchmark.h>

#include "ccma/ccma.h"
#include "ccma/internal/dense_factorizations.h"

namespace {

using namespace ccma;
using Method = RankRevealingDecomposition::Method;

std::vector<Eigen::MatrixXd>* captured = nullptr;

void Record(const Eigen::MatrixXd& A, const RankRevealingDecomposition::Threshold&, Method) {
  if (captured != nullptr) captured->push_back(A);
}

// The first matrix `site` gives a decomposition; empty when none.
template <typename Site>
Eigen::MatrixXd Capture(Site site) {
  std::vector<Eigen::MatrixXd> out;
  captured = &out;
  SetRankDecisionObserver(&Record);
  site();
  SetRankDecisionObserver(nullptr);
  captured = nullptr;
  return out.empty() ? Eigen::MatrixXd() : out.front();
}

Model Stewart(int agents, bool compliant) {
  StewartOptions options;
  options.agents = agents;
  options.base_radius = agents > 6 ? 3.0 : options.base_radius;
  Model model = LoadModelFromString(GenerateStewartModel(options), "generated.yaml");
  if (!compliant) return model;
  model.end_effector.payload.mass = 2.0;
  for (MobileBase& base : model.mobile_bases) base.stiffness.k = Eigen::Vector3d(2e4, 2e4, 500);
  for (Joint& joint : model.joints) {
    if (joint.type == JointType::kRevolute) joint.stiffness.rotation = {2e3, 2e3};
  }
  return model;
}

Eigen::MatrixXd MovedComponentsMatrix(const Model& model) {
  ComponentSet all;
  all.fill(true);
  return Capture([&] { AnalyzeMovedComponents(model, State::Home(model), model.home_controls(), all); });
}

// Home against home with the first body that is not the end-effector's
// moved: the same pose, a state difference, so the idle motions are listed.
Eigen::MatrixXd IdleMotionsMatrix(const Model& model) {
  const State a = State::Home(model);
  State b = a;
  const int body = model.end_effector.body == 0 ? 1 : 0;
  b.SetPose(body, a.q_WB(body), a.p_WB(body) + Eigen::Vector3d(1e-3, 0, 0));
  return Capture([&] { CompareConfigurations(model, a, b, model.home_controls()); });
}

Eigen::MatrixXd CompliantMatrix(const Model& model) {
  ForwardProblem forward(model);
  if (!forward.Solve(model.home_controls()).assembled) return Eigen::MatrixXd();
  return Capture([&] { ComputeStatics(model, forward.state(), forward.controls()); });
}

void BM_Bdcsvd(benchmark::State& state, const Eigen::MatrixXd& A) {
  for (auto _ : state) {
    const Eigen::BDCSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
    benchmark::DoNotOptimize(svd.matrixV().data());
  }
}

void BM_Decision(benchmark::State& state, const Eigen::MatrixXd& A, Method method) {
  // A threshold as the sites': 1e-8 of the largest singular value.
  const double threshold = 1e-8 * std::max(1.0, JacobiSvd(A).singularValues()[0]);
  for (auto _ : state) {
    const RankRevealingDecomposition d(A, {threshold, 0.0}, method);
    benchmark::DoNotOptimize(d.nullSpace().data());
  }
}

void Register(const std::string& name, const Eigen::MatrixXd& A) {
  if (A.size() == 0) {
    std::cerr << name << ": no matrix captured\n";
    return;
  }
  const std::string label = name + "/" + std::to_string(A.rows()) + "x" + std::to_string(A.cols());
  benchmark::RegisterBenchmark((label + "/bdcsvd").c_str(), BM_Bdcsvd, A)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark((label + "/jacobi").c_str(), BM_Decision, A, Method::kJacobiSvd)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark((label + "/qr").c_str(), BM_Decision, A, Method::kPivotedQr)
      ->Unit(benchmark::kMillisecond);
}

}  // namespace

int main(int argc, char** argv) {
  const Model six = LoadModel(std::string(CCMA_MODELS_DIR) + "/6dof_six_agents.yaml");
  Register("moved_components/6dof_six_agents", MovedComponentsMatrix(six));
  Register("idle_motions/6dof_six_agents", IdleMotionsMatrix(six));
  for (const int agents : {12, 24, 33}) {  // 33 agents: state size 600, the largest the dense sites take
    const Model model = Stewart(agents, false);
    const std::string name = "stewart_" + std::to_string(agents);
    Register("moved_components/" + name, MovedComponentsMatrix(model));
    Register("idle_motions/" + name, IdleMotionsMatrix(model));
  }
  for (const int agents : {6, 48}) {
    Register("compliant/stewart_" + std::to_string(agents), CompliantMatrix(Stewart(agents, true)));
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
