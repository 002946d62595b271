// Warm-started forward solve after one paper-size control step, per
// reference model and solver: ccma's native sparse LM (the default) and
// Ceres with each linear solver (Google Benchmark), in one run.
//
// Each iteration moves the controls between two reachable configurations:
// home, and the closed-form controls (tests/leg_closed_form.h) of an
// end-effector pose 10 mm + 0.005 rad away, the paper's control step, which
// moves the bases by about 1 cm. The solve warm-starts from the previous
// solution, as in a control loop.
//   build/benchmarks/forward_benchmark --benchmark_repetitions=10 \
//       --benchmark_report_aggregates_only=true
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "ccma/ccma.h"
#include "tests/leg_closed_form.h"

namespace {

using ccma::ForwardOptions;
using ccma::ForwardProblem;
using ccma::LinearSolverChoice;

Eigen::VectorXd StepControls(const ccma::Model& m) {
  const Eigen::Vector3d direction = Eigen::Vector3d(1, 1, 1).normalized();
  const Eigen::Vector3d p = m.end_effector.p_W_home + 0.010 * direction;
  const Eigen::Matrix3d R = ccma::RotationFromRpy(
      m.end_effector.controlled[ccma::kRoll] ? Eigen::Vector3d(0.005, 0.005, 0.005) / std::sqrt(3.0)
                                              : Eigen::Vector3d(0, 0, 0.005));
  Eigen::VectorXd u = m.home_controls();
  for (const auto& leg : ccma::testing::FindLegs(m)) {
    u.segment<3>(3 * leg.base) = ccma::testing::BasePoseForLeg(m, leg, p, R, 0.0);
  }
  return u;
}

void BM_ForwardWarmStep(benchmark::State& state, const std::string& name, ccma::ForwardSolver minimiser,
                        LinearSolverChoice solver) {
  const ccma::Model model = ccma::LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
  ForwardOptions options;
  options.solver = minimiser;
  options.linear_solver = solver;
  ForwardProblem forward(model, options);
  const Eigen::VectorXd u[2] = {model.home_controls(), StepControls(model)};
  const double base_move = (u[1] - u[0]).lpNorm<Eigen::Infinity>();
  forward.Solve(u[0]);
  int which = 1;
  long iterations = 0, solves = 0, assembled = 0;
  for (auto _ : state) {
    const ccma::ForwardResult r = forward.Solve(u[which]);
    which ^= 1;
    iterations += r.iterations;
    assembled += r.assembled;
    ++solves;
  }
  state.counters["iterations"] = double(iterations) / solves;
  state.counters["assembled_fraction"] = double(assembled) / solves;
  state.counters["max_control_change_mm"] = 1000 * base_move;
  state.counters["state_size"] = model.state_size();
}

// A 200-step track, as a simulation loop runs one: the end-effector goes
// once round a circle of radius 5 cm (controls in closed form,
// tests/leg_closed_form.h), steps of ~1.6 mm; each solve warm-starts from
// the last (and, for the native solver with `predictors`, from its secant or
// rigid-motion prediction). Horizontal circle: every base moves by the
// end-effector's displacement, the mechanism translates rigidly and the
// rigid-motion predictor ends each step without an iteration. Vertical
// circle: the legs fold, every step iterates. Time per step.
void BM_ForwardTrack(benchmark::State& state, const std::string& name, ccma::ForwardSolver minimiser,
                     bool predictors, bool vertical) {
  const ccma::Model model = ccma::LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
  std::vector<Eigen::VectorXd> track;
  constexpr int kSteps = 200;
  for (int k = 0; k <= kSteps; ++k) {
    const double angle = 2 * M_PI * k / kSteps;
    const Eigen::Vector3d p =
        model.end_effector.p_W_home +
        0.05 * (vertical ? Eigen::Vector3d(std::cos(angle) - 1, 0, std::sin(angle))
                         : Eigen::Vector3d(std::cos(angle) - 1, std::sin(angle), 0));
    Eigen::VectorXd u = model.home_controls();
    for (const auto& leg : ccma::testing::FindLegs(model)) {
      u.segment<3>(3 * leg.base) = ccma::testing::BasePoseForLeg(model, leg, p, Eigen::Matrix3d::Identity(), 0.0);
    }
    track.push_back(u);
  }
  ForwardOptions options;
  options.solver = minimiser;
  options.secant_predictor = predictors;
  options.rigid_motion_predictor = predictors;
  ForwardProblem forward(model, options);
  long iterations = 0, solves = 0, assembled = 0;
  double worst_energy = 0;
  for (auto _ : state) {
    for (int k = 1; k <= kSteps; ++k) {
      const ccma::ForwardResult r = forward.Solve(track[k]);
      iterations += r.iterations;
      assembled += r.assembled;
      worst_energy = std::max(worst_energy, r.residual_energy);
      ++solves;
    }
  }
  state.SetItemsProcessed(solves);
  state.counters["us_per_step"] =
      benchmark::Counter(static_cast<double>(solves), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["iterations"] = double(iterations) / solves;
  state.counters["assembled_fraction"] = double(assembled) / solves;
  state.counters["worst_E"] = worst_energy;
}

// The fixed cost of one Solve() call: controls unchanged, nothing to do but
// the solver's preprocessing and one evaluation. Subtract it to see the iterations.
void BM_ForwardAtRest(benchmark::State& state, const std::string& name, ccma::ForwardSolver minimiser) {
  const ccma::Model model = ccma::LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
  ForwardOptions options;
  options.solver = minimiser;
  ForwardProblem forward(model, options);
  const Eigen::VectorXd u = model.home_controls();
  for (auto _ : state) benchmark::DoNotOptimize(forward.Solve(u));
}

const std::vector<std::string> kModels = {"4dof_reduced", "4dof_complete", "6dof_symmetric",
                                          "6dof_asymmetric", "6dof_six_agents"};

int Register() {
  using ccma::ForwardSolver;
  const std::vector<std::tuple<std::string, ForwardSolver, LinearSolverChoice>> solvers = {
      {"native", ForwardSolver::kNative, LinearSolverChoice::kAuto},
      {"ceres_auto", ForwardSolver::kCeres, LinearSolverChoice::kAuto},
      {"ceres_dense_qr", ForwardSolver::kCeres, LinearSolverChoice::kDenseQr},
      {"ceres_dense_normal_cholesky", ForwardSolver::kCeres, LinearSolverChoice::kDenseNormalCholesky},
      {"ceres_suitesparse_normal_cholesky", ForwardSolver::kCeres, LinearSolverChoice::kSparseNormalCholesky},
      {"ceres_eigen_sparse_normal_cholesky", ForwardSolver::kCeres, LinearSolverChoice::kEigenSparseNormalCholesky}};
  for (const std::string& model : kModels) {
    for (const auto& [name, minimiser] : {std::pair{"native", ForwardSolver::kNative},
                                          std::pair{"ceres", ForwardSolver::kCeres}}) {
      benchmark::RegisterBenchmark(("ForwardAtRest/" + model + "/" + name).c_str(), BM_ForwardAtRest, model,
                                   minimiser)
          ->Unit(benchmark::kMicrosecond);
    }
  }
  for (const std::string& model : {std::string("4dof_reduced"), std::string("6dof_six_agents")}) {
    for (const bool vertical : {false, true}) {
      const std::string track = "ForwardTrack/" + model + (vertical ? "/vertical/" : "/horizontal/");
      benchmark::RegisterBenchmark((track + "native").c_str(), BM_ForwardTrack, model, ForwardSolver::kNative,
                                   true, vertical)->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark((track + "native_no_predictor").c_str(), BM_ForwardTrack, model,
                                   ForwardSolver::kNative, false, vertical)->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark((track + "ceres").c_str(), BM_ForwardTrack, model, ForwardSolver::kCeres,
                                   false, vertical)->Unit(benchmark::kMillisecond);
    }
  }
  for (const auto& [solver_name, minimiser, solver] : solvers) {
    for (const std::string& model : kModels) {
      benchmark::RegisterBenchmark(("ForwardWarmStep/" + model + "/" + solver_name).c_str(),
                                   BM_ForwardWarmStep, model, minimiser, solver)
          ->Unit(benchmark::kMicrosecond);
    }
  }
  return 0;
}
const int kRegistered = Register();

}  // namespace

BENCHMARK_MAIN();
