// `ccma bench`: the paper's convergence-timing study (its Fig. 6), with every
// baseline measured in the same run.
//   ccma bench --model=FILE [--steps=20] [--seed=1] [--out=DIR]
//   ccma bench --all [--models_dir=models] [--steps=20] [--out=DIR]
//   ccma bench --scaling [--steps=10] [--out=DIR]
// Each model walks a seeded out-and-back path of paper-size combined steps
// (10 mm + 0.005 rad); every step is solved by LM and by BFGS, each with
// implicit-function gradients and with finite differences (2k solves).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <numeric>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <thread>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "ccma/internal/format.h"
#include "apps/flags.h"
#include "apps/commands.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "apps/plots.h"
#include "apps/work_bound.h"
#include "ccma/internal/constraint_set.h"

DEFINE_int32(steps, 0, "path steps per model, 1..10000 (default 20; 10 with --scaling) [steps]");
DEFINE_bool(all, false, "benchmark every .yaml model in --models_dir [flag]");
DEFINE_bool(scaling, false, "benchmark generated models with 3, 6, 12, 24, 48 agents [flag]");
DEFINE_string(models_dir, "", "bench --all: folder of models (default: models/ here, else the source tree's) [path]");

namespace ccma::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct Stats {
  double median = 0, p95 = 0;
};

Stats Summarize(std::vector<double> v) {
  Stats s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  s.p95 = v[std::min(n - 1, static_cast<size_t>(std::ceil(0.95 * n)) - 1)];
  return s;
}

nlohmann::json Machine() {
  std::string cpu = "unknown";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  return {{"cpu", cpu}, {"cores", std::thread::hardware_concurrency()}, {"build_type", CCMA_BUILD_TYPE}};
}

// Out and back: steps/2 seeded combined steps (10 mm along a random
// direction, 0.005 rad about a random axis, or about z for models that do
// not control roll and pitch), then the same targets in reverse to home.
std::vector<PoseTarget> SeededPath(const Model& m, const PoseTarget& home, int steps, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n;
  const bool tilts = m.end_effector.controlled[kRoll] || m.end_effector.controlled[kPitch];
  std::vector<PoseTarget> out;
  PoseTarget current = home;
  const int half = (steps + 1) / 2;
  for (int i = 0; i < half; ++i) {
    const Eigen::Vector3d direction = Eigen::Vector3d{n(rng), n(rng), n(rng)}.normalized();
    const Eigen::Vector3d axis = tilts ? Eigen::Vector3d{n(rng), n(rng), n(rng)}.normalized()
                                       : Eigen::Vector3d(0, 0, n(rng) > 0 ? 1 : -1);
    current.position += 0.010 * direction;
    current.rpy = RpyFromRotation(QuaternionExp(0.005 * axis).toRotationMatrix() * RotationFromRpy(current.rpy));
    out.push_back(current);
  }
  for (int i = half - 2; i >= 0 && static_cast<int>(out.size()) < steps - 1; --i) out.push_back(out[i]);
  if (static_cast<int>(out.size()) < steps) out.push_back(home);
  return out;
}

struct StepRecord {
  std::string method, gradient;
  int step;
  ControlStepResult result;
};

struct Curve {
  std::vector<std::array<double, 3>> points;  // time_ms, objective, error
};

// Walks the path with one outer loop and gradient method; records every step
// and, for the second step, the convergence curve.
std::vector<StepRecord> Walk(const Model& model, const std::vector<PoseTarget>& path, ControlMethod method,
                             GradientMethod gradient, int max_steps, Curve* curve,
                             std::vector<double>* forward_us, WorkEstimate* bound, long long* done) {
  ControlOptions options;
  options.method = method;
  options.gradient = gradient;
  int current_step = 0;
  if (curve != nullptr) {
    options.on_iteration = [&](int, double ms, double objective, double error) {
      // The second step: warm, like every later one (the first pays one-off costs).
      if (current_step == 1) curve->points.push_back({ms, objective, error});
    };
  }
  ControlProblem control(model, options);
  ForwardProblem tracking(model);  // the warm forward solve at each step's controls
  std::vector<StepRecord> records;
  for (int i = 0; i < std::min<int>(max_steps, path.size()); ++i) {
    current_step = i;
    const ControlStepResult r = control.SolveStep(path[i]);
    records.push_back({method == ControlMethod::kBfgs ? "bfgs" : "lm",
                       gradient == GradientMethod::kImplicit ? "implicit" : "finite_difference", i, r});
    if (forward_us != nullptr) forward_us->push_back(1000.0 * tracking.Solve(control.controls()).solve_time_ms);
    bound->Update(++*done);
  }
  return records;
}

nlohmann::json LoopJson(const std::vector<StepRecord>& records) {
  std::vector<double> ms, iterations;
  int reached = 0;
  for (const auto& r : records) {
    ms.push_back(r.result.time_ms);
    iterations.push_back(r.result.iterations);
    reached += r.result.reached;
  }
  const Stats t = Summarize(ms);
  return {{"median", t.median},
          {"p95", t.p95},
          {"median_iterations", Summarize(iterations).median},
          {"steps", records.size()},
          {"reached_fraction", records.empty() ? 0.0 : double(reached) / records.size()}};
}

// Median time [us] to evaluate every cost function with its Jacobians once:
// analytic (tangent Jacobians directly) or autodiff twins (ambient Jacobians
// projected onto the tangent, the work Ceres would add).
nlohmann::json JacobianTiming(const Model& model) {
  const ConstraintSet constraints(model);
  const auto twins = constraints.MakeAutoDiffTwins(model);
  const State s = State::Home(model);
  const Eigen::VectorXd u = model.home_controls();
  double residuals[9], jac[3][9 * 7], tangent[9 * 6];
  double* jacobians[3] = {jac[0], jac[1], jac[2]};
  std::vector<const double*> params;
  double sink = 0;
  auto evaluate_all = [&](bool autodiff) {
    for (size_t b = 0; b < constraints.blocks().size(); ++b) {
      const ConstraintBlock& block = constraints.blocks()[b];
      params.clear();
      for (int body : block.bodies) params.push_back(ConstraintSet::Pose(s, body));
      if (block.control_size > 0) params.push_back(u.data() + block.control_offset);
      const ceres::CostFunction& cost = autodiff ? *twins[b] : *block.cost;
      cost.Evaluate(params.data(), residuals, jacobians);
      if (autodiff) {
        for (size_t p = 0; p < block.bodies.size(); ++p) {
          const double* q = params[p];
          Eigen::Matrix<double, 7, 6> P = Eigen::Matrix<double, 7, 6>::Zero();
          P.block<3, 3>(0, 0) = 0.5 * (q[3] * Eigen::Matrix3d::Identity() - Skew(Eigen::Vector3d(q[0], q[1], q[2])));
          P.block<1, 3>(3, 0) = -0.5 * Eigen::Vector3d(q[0], q[1], q[2]).transpose();
          P.block<3, 3>(4, 3).setIdentity();
          using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
          Eigen::Map<RowMajor>(tangent, block.rows, 6).noalias() =
              Eigen::Map<const RowMajor>(jac[p], block.rows, 7) * P;
          sink += tangent[0];
        }
      }
      sink += jac[0][0];
    }
  };
  nlohmann::json out;
  for (const bool autodiff : {false, true}) {
    std::vector<double> us;
    for (int batch = 0; batch < 60; ++batch) {
      const auto start = Clock::now();
      for (int i = 0; i < 20; ++i) evaluate_all(autodiff);
      us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count() / 20);
    }
    out[autodiff ? "autodiff" : "analytic"] = Summarize(us).median;
  }
  if (sink == 12345.678) std::cerr << "";  // keep the work
  return out;
}

std::string ModelsDir() {
  if (!FLAGS_models_dir.empty()) return FLAGS_models_dir;
  return std::filesystem::is_directory("models") ? "models" : CCMA_MODELS_DIR;
}

void WriteCurve(const std::string& path, const Curve& curve) {
  std::ofstream out(path);
  out << "# time_ms objective error\n" << std::setprecision(10);
  for (const auto& p : curve.points) out << p[0] << " " << p[1] << " " << p[2] << "\n";
}

// The control steps one model's walks solve (BenchModel).
long long StepsPerModel(int steps) { return 3LL * steps + std::min(steps, 4); }

nlohmann::json BenchModel(const Model& model, int steps, const std::string& out_dir, WorkEstimate* bound) {
  long long done = 0;
  ForwardProblem probe(model);
  const PoseTarget home{probe.end_effector().position, probe.end_effector().rpy};
  const std::vector<PoseTarget> path = SeededPath(model, home, steps, FLAGS_seed);
  std::vector<double> forward_us;
  Curve lm_curve, bfgs_curve;
  const auto lm = Walk(model, path, ControlMethod::kLevenbergMarquardt, GradientMethod::kImplicit, steps,
                       &lm_curve, &forward_us, bound, &done);
  const auto bfgs = Walk(model, path, ControlMethod::kBfgs, GradientMethod::kImplicit, steps, &bfgs_curve, nullptr,
                         bound, &done);
  const auto lm_fd = Walk(model, path, ControlMethod::kLevenbergMarquardt, GradientMethod::kFiniteDifference,
                          steps, nullptr, nullptr, bound, &done);
  // BFGS with finite differences costs ~100 solves per iteration: a few steps.
  const auto bfgs_fd = Walk(model, path, ControlMethod::kBfgs, GradientMethod::kFiniteDifference,
                            std::min(steps, 4), nullptr, nullptr, bound, &done);

  nlohmann::json out;
  out["model"] = model.name;
  out["steps"] = path.size();
  out["state_size"] = model.state_size();
  const Stats fwd = Summarize(forward_us);
  out["forward_us"] = {{"median", fwd.median}, {"p95", fwd.p95}};
  out["control_ms"] = {{"lm", LoopJson(lm)}, {"bfgs", LoopJson(bfgs)}};
  const nlohmann::json fd_lm = LoopJson(lm_fd), fd_bfgs = LoopJson(bfgs_fd);
  out["finite_difference_ms"] = {{"median", fd_lm["median"]}, {"lm", fd_lm}, {"bfgs", fd_bfgs}};
  out["speedup_over_finite_differences"] = {
      {"lm", fd_lm["median"].get<double>() / out["control_ms"]["lm"]["median"].get<double>()},
      {"bfgs", fd_bfgs["median"].get<double>() / out["control_ms"]["bfgs"]["median"].get<double>()}};
  out["jacobian_us"] = JacobianTiming(model);
  out["machine"] = Machine();

  if (!out_dir.empty()) {
    std::ofstream csv(out_dir + "/" + model.name + "_steps.csv");
    csv << "step,method,gradient,time_ms,iterations,forward_solves,reached,error,residual_energy,forward_us\n"
        << std::setprecision(10);
    for (const auto* records : {&lm, &bfgs, &lm_fd, &bfgs_fd}) {
      for (const StepRecord& r : *records) {
        csv << r.step << "," << r.method << "," << r.gradient << "," << r.result.time_ms << ","
            << r.result.iterations << "," << r.result.forward_solves << "," << r.result.reached << ","
            << r.result.error << "," << r.result.residual_energy << ","
            << (records == &lm ? forward_us[r.step] : 0.0) << "\n";
      }
    }
    WriteCurve(out_dir + "/" + model.name + "_convergence_lm.dat", lm_curve);
    WriteCurve(out_dir + "/" + model.name + "_convergence_bfgs.dat", bfgs_curve);
  }
  return out;
}

nlohmann::json Scaling(int steps, WorkEstimate* bound) {
  nlohmann::json rows = nlohmann::json::array();
  std::vector<double> log_n, log_forward, log_control;
  for (int agents : {3, 6, 12, 24, 48}) {
    // Each size a stage of its own: its steps cost more than the last's.
    if (agents > 3) bound->BeginStage("control steps of " + std::to_string(agents) + " agents", steps, 0, true);
    long long done = 0;
    StewartOptions options;
    options.agents = agents;
    const Model model = LoadModelFromString(GenerateStewartModel(options), "generated");
    ForwardProblem probe(model);
    const PoseTarget home{probe.end_effector().position, probe.end_effector().rpy};
    const auto path = SeededPath(model, home, steps, FLAGS_seed);
    std::vector<double> forward_us;
    const auto lm = Walk(model, path, ControlMethod::kLevenbergMarquardt, GradientMethod::kImplicit, steps,
                         nullptr, &forward_us, bound, &done);
    const nlohmann::json control = LoopJson(lm);
    const double forward = Summarize(forward_us).median;
    rows.push_back({{"agents", agents},
                    {"state_size", model.state_size()},
                    {"forward_us_median", forward},
                    {"control_ms_median", control["median"]},
                    {"control_median_iterations", control["median_iterations"]},
                    {"reached_fraction", control["reached_fraction"]}});
    if (agents >= 6) {
      log_n.push_back(std::log(agents));
      log_forward.push_back(std::log(forward));
      log_control.push_back(std::log(control["median"].get<double>()));
    }
  }
  auto slope = [&](const std::vector<double>& y) {
    const double mx = std::accumulate(log_n.begin(), log_n.end(), 0.0) / log_n.size();
    const double my = std::accumulate(y.begin(), y.end(), 0.0) / y.size();
    double sxy = 0, sxx = 0;
    for (size_t i = 0; i < y.size(); ++i) {
      sxy += (log_n[i] - mx) * (y[i] - my);
      sxx += (log_n[i] - mx) * (log_n[i] - mx);
    }
    return sxy / sxx;
  };
  return {{"scaling", rows},
          {"fit", "least squares of log(median time) on log(agents), 6 to 48 agents"},
          {"forward_exponent", slope(log_forward)},
          {"control_exponent", slope(log_control)},
          {"machine", Machine()}};
}

// The tables of benchmarks/RESULTS.md, written next to the data.
void WriteModelTable(const std::string& path, const nlohmann::json& results) {
  std::ofstream md(path);
  const auto& machine = results[0]["machine"];
  md << "Machine: " << machine["cpu"].get<std::string>() << ", " << machine["cores"] << " cores, "
     << machine["build_type"].get<std::string>() << " build. " << results[0]["steps"]
     << " paper-size steps per model (10 mm + 0.005 rad, seeded, out and back); medians (p95).\n\n"
     << "| model | state size | forward solve [us] | control step, LM [ms] | control step, BFGS [ms] | "
        "LM, finite differences [ms] | BFGS, finite differences [ms] | speed-up LM / BFGS | "
        "Jacobians analytic / autodiff [us] |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : results) {
    auto loop = [](const nlohmann::json& l) {
      return FormatFixed(l["median"], 3) + " (" + FormatFixed(l["p95"], 3) + "), " + FormatFixed(l["median_iterations"], 0) +
             " it" + (l["reached_fraction"].get<double>() < 1 ? ", reached " + FormatFixed(100 * l["reached_fraction"].get<double>(), 0) + "%" : "");
    };
    md << "| " << r["model"].get<std::string>() << " | " << r["state_size"] << " | "
       << FormatFixed(r["forward_us"]["median"], 1) << " (" << FormatFixed(r["forward_us"]["p95"], 1) << ") | "
       << loop(r["control_ms"]["lm"]) << " | " << loop(r["control_ms"]["bfgs"]) << " | "
       << loop(r["finite_difference_ms"]["lm"]) << " | " << loop(r["finite_difference_ms"]["bfgs"]) << " | "
       << FormatFixed(r["speedup_over_finite_differences"]["lm"], 1) << "x / "
       << FormatFixed(r["speedup_over_finite_differences"]["bfgs"], 1) << "x | "
       << FormatFixed(r["jacobian_us"]["analytic"], 2) << " / " << FormatFixed(r["jacobian_us"]["autodiff"], 2) << " |\n";
  }
}

void WriteScalingTable(const std::string& path, const nlohmann::json& scaling) {
  std::ofstream md(path);
  const auto& machine = scaling["machine"];
  md << "Machine: " << machine["cpu"].get<std::string>() << ", " << machine["cores"] << " cores, "
     << machine["build_type"].get<std::string>() << " build. Generated Stewart-like models "
     << "(`ccma generate`); medians over the path's steps.\n\n"
     << "| agents | state size | forward solve [us] | control step, LM [ms] | LM iterations |\n"
     << "|---|---|---|---|---|\n";
  for (const auto& r : scaling["scaling"]) {
    md << "| " << r["agents"] << " | " << r["state_size"] << " | " << FormatFixed(r["forward_us_median"], 1) << " | "
       << FormatFixed(r["control_ms_median"], 3) << " | " << FormatFixed(r["control_median_iterations"], 0) << " |\n";
  }
  md << "\nFitted growth exponents from 6 to 48 agents (" << scaling["fit"].get<std::string>()
     << "): forward solve " << FormatFixed(scaling["forward_exponent"], 2) << ", control step "
     << FormatFixed(scaling["control_exponent"], 2) << ".\n";
}

// The models to bench: --model, or with --all every .yaml in --models_dir.
std::vector<Model> BenchModels() {
  std::vector<Model> models;
  if (!FLAGS_all) {
    models.push_back(LoadModelOrThrow(FLAGS_model));
    return models;
  }
  const std::string dir = ModelsDir();
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    throw UsageError("ccma bench --all: --models_dir: '" + dir + "' is not a directory");
  }
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) throw UsageError("ccma bench --all: no .yaml models in '" + dir + "'");
  for (const auto& f : files) models.push_back(LoadModelOrThrow(f));
  return models;
}

}  // namespace

int RunBench(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "bench");
  if (FLAGS_seed < 0) throw UsageError("ccma bench: --seed must not be negative");
  const int modes = !FLAGS_model.empty() + FLAGS_all + FLAGS_scaling;
  if (modes != 1) throw UsageError("ccma bench: give exactly one of --model=FILE, --all, --scaling");
  const int steps = FLAGS_steps > 0 ? FLAGS_steps : (FLAGS_scaling ? 10 : 20);
  if (FLAGS_steps < 0 || steps > 10000) throw UsageError("ccma bench: --steps must be between 1 and 10000");
  const WorkEstimateOptions bound_options = CommandWorkEstimate("bench", "control steps", false);
  std::unique_ptr<OutputDirectory> output;
  if (!FLAGS_out.empty()) output = std::make_unique<OutputDirectory>(FLAGS_out, "ccma bench");
  // Work bounded by its cost (--max_minutes): the control steps timed as
  // they are solved, each model (each size) a stage of its own.
  if (FLAGS_scaling) {
    WorkEstimate bound(bound_options, steps);
    const nlohmann::json scaling = Scaling(steps, &bound);
    if (!FLAGS_out.empty()) {
      FolderOutput folder(FLAGS_out, "out");
      WriteScalingTable(folder.scratch() + "/scaling.md", scaling);
      folder.Commit();
      output->Keep();
    }
    PrintJson(scaling);
    return 0;
  }
  const std::vector<Model> models = BenchModels();
  nlohmann::json results = nlohmann::json::array();
  std::vector<std::string> names;
  // The files are written in a private scratch folder and moved into --out
  // at the end (apps/output_file.h): a link planted in --out is replaced,
  // never written through.
  std::unique_ptr<FolderOutput> folder;
  if (!FLAGS_out.empty()) folder = std::make_unique<FolderOutput>(FLAGS_out, "out");
  WorkEstimate bound(bound_options, StepsPerModel(steps));
  for (size_t m = 0; m < models.size(); ++m) {
    const Model& model = models[m];
    std::cerr << "ccma bench: " << model.name << " ..." << std::endl;
    if (m > 0) bound.BeginStage("control steps of " + model.name, StepsPerModel(steps), 0, true);
    results.push_back(BenchModel(model, steps, folder ? folder->scratch() : "", &bound));
    names.push_back(model.name);
  }
  if (folder) {
    std::string warning;
    nlohmann::json plots = nlohmann::json::array();
    for (const std::string& file : PlotConvergence(folder->scratch(), names, &warning)) {
      plots.push_back(folder->Final(file));
    }
    if (!warning.empty()) std::cerr << "ccma bench: " << warning << "\n";
    for (auto& r : results) r["plots"] = plots;
    WriteModelTable(folder->scratch() + "/models.md", results);
    folder->Commit();
    output->Keep();
  }
  PrintJson(FLAGS_all ? results : results[0]);
  return 0;
}

}  // namespace ccma::cli
