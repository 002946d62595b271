// One paper-size control step (end-effector moved 10 mm + 0.005 rad, the
// paper's Section III-C step), per reference model and outer loop, with
// gradients from implicit-function sensitivities and, in the same run, from
// central finite differences of re-solved forward problems (2k solves).
// Each iteration alternates between the home pose and the moved pose, so
// every step starts from the previous solution, as in a control loop.
// Gradient/...: the derivatives alone, at the assembled home state, towards
// the moved target, on every bundled model: dO/du (the BFGS gradient: one
// adjoint solve against 2k forward solves) and ds/du (the LM Jacobian's core:
// one factorisation and k solves against 2k forward solves).
//   build/benchmarks/control_benchmark --benchmark_repetitions=5 \
//       --benchmark_report_aggregates_only=true
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "ccma/ccma.h"
#include "benchmarks/paper_step.h"

namespace {

using namespace ccma;


void BM_ControlStep(benchmark::State& state, const std::string& name, ControlMethod method,
                    GradientMethod gradient) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
  ControlOptions options;
  options.method = method;
  options.gradient = gradient;
  ControlProblem control(model, options);
  const PoseTarget targets[2] = {control.CurrentPose(), PaperStep(model, control.CurrentPose())};
  int which = 1;
  long iterations = 0, solves = 0, steps = 0, reached = 0;
  for (auto _ : state) {
    const ControlStepResult r = control.SolveStep(targets[which]);
    which ^= 1;
    iterations += r.iterations;
    solves += r.forward_solves;
    reached += r.reached;
    ++steps;
  }
  state.counters["outer_iterations"] = double(iterations) / steps;
  state.counters["forward_solves"] = double(solves) / steps;
  state.counters["reached_fraction"] = double(reached) / steps;
}

enum class Derivative { kObjectiveGradient, kStateSensitivity };

void BM_Gradient(benchmark::State& state, const std::string& name, Derivative derivative, GradientMethod gradient) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
  ControlOptions options;
  options.gradient = gradient;
  ControlProblem control(model, options);
  if (!control.SetControls(model.home_controls()).assembled) {
    state.SkipWithError("home does not assemble");
    return;
  }
  const PoseTarget target = PaperStep(model, control.CurrentPose());
  Eigen::VectorXd dO_du;
  double checksum = 0;
  for (auto _ : state) {
    if (derivative == Derivative::kObjectiveGradient) {
      control.Objective(target, &dO_du);
      checksum += dO_du[0];
    } else {
      checksum += control.StateSensitivity()(0, 0);
    }
  }
  benchmark::DoNotOptimize(checksum);
  state.counters["controls"] = static_cast<double>(control.effective_controls().size());
}

int Register() {
  const std::vector<std::string> models = {"4dof_reduced", "4dof_complete", "6dof_symmetric",
                                           "6dof_asymmetric", "6dof_six_agents"};
  for (const auto& [method_name, method] :
       std::vector<std::pair<std::string, ControlMethod>>{{"lm", ControlMethod::kLevenbergMarquardt},
                                                          {"bfgs", ControlMethod::kBfgs}}) {
    for (const auto& [gradient_name, gradient] :
         std::vector<std::pair<std::string, GradientMethod>>{{"implicit", GradientMethod::kImplicit},
                                                             {"finite_difference", GradientMethod::kFiniteDifference}}) {
      for (const std::string& model : models) {
        benchmark::RegisterBenchmark(("ControlStep/" + model + "/" + method_name + "/" + gradient_name).c_str(),
                                     BM_ControlStep, model, method, gradient)
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }
  const std::vector<std::string> all_models = {"4dof_reduced",    "4dof_complete",   "4dof_differential",
                                               "6dof_symmetric",  "6dof_asymmetric", "6dof_six_agents",
                                               "hybrid_ccma",     "planar_3rpr",     "stewart_gough_6ups"};
  for (const auto& [derivative_name, derivative] : std::vector<std::pair<std::string, Derivative>>{
           {"dO_du", Derivative::kObjectiveGradient}, {"ds_du", Derivative::kStateSensitivity}}) {
    for (const std::string& model : all_models) {
      for (const auto& [gradient_name, gradient] :
           std::vector<std::pair<std::string, GradientMethod>>{{"implicit", GradientMethod::kImplicit},
                                                               {"finite_difference", GradientMethod::kFiniteDifference}}) {
        benchmark::RegisterBenchmark(("Gradient/" + derivative_name + "/" + model + "/" + gradient_name).c_str(),
                                     BM_Gradient, model, derivative, gradient)
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }
  return 0;
}
const int kRegistered = Register();

}  // namespace

BENCHMARK_MAIN();
