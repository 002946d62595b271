#include "benchmarks/simbody/report.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include <Simbody.h>
#include <nlohmann/json.hpp>

namespace ccma::simbody_benchmark {
namespace {

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

// "median (p95)" of a solver's step times; "n/a" when it did not run.
std::string TimeCell(const StepSamples& s) {
  if (s.time_us.empty()) return "n/a";
  return Format("%.1f", Median(s.time_us)) + " (" + Format("%.1f", Quantile(s.time_us, 0.95)) + ")";
}

// The other's median time over ccma's: how many times faster ccma is.
std::string SpeedUpCell(const StepSamples& ccma, const StepSamples& other) {
  if (other.time_us.empty()) return "n/a";
  return Format("%.1f", Median(other.time_us) / Median(ccma.time_us)) + "x";
}

nlohmann::json SolverJson(const StepSamples& s) {
  if (s.time_us.empty()) return nullptr;
  return {{"median_us", Median(s.time_us)},
          {"p95_us", Quantile(s.time_us, 0.95)},
          {"min_us", Quantile(s.time_us, 0.0)},
          {"median_iterations", Median(s.iterations)},
          {"max_iterations", Quantile(s.iterations, 1.0)},
          {"steps", s.time_us.size()},
          {"failed_steps", s.failures}};
}

}  // namespace

Machine DescribeMachine() {
  Machine machine;
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) machine.cpu = line.substr(line.find_first_not_of(' ', colon + 1));
      break;
    }
  }
  if (machine.cpu.empty()) machine.cpu = "unknown CPU";
  machine.cores = static_cast<int>(std::thread::hardware_concurrency());
  int major = 0, minor = 0, build = 0;
  SimTK_version_simbody(&major, &minor, &build);
  machine.simbody_version = std::to_string(major) + "." + std::to_string(minor) +
                            (build ? "." + std::to_string(build) : std::string());
  return machine;
}

std::string MarkdownReport(const Machine& machine, const std::vector<HeadToHeadResult>& results) {
  std::ostringstream out;
  if (!results.empty()) {
    const HeadToHeadResult& first = results.front();
    out << "Machine: " << machine.cpu << ", " << machine.cores << " cores; Simbody " << machine.simbody_version
        << " (Debian's build); ccma Release build. Paths: " << first.steps << "-step circles (r = 5 cm) x " << first.laps
        << " laps, warm; Simbody tolerance " << Format("%.0e", first.tolerance)
        << " on every constraint. Times: median (p95) per step.\n\n"
        << "All solvers interleaved step by step (each finds the caches filled by the others):\n\n";
  }
  out << "| model | path | ccma [us/step] | Simbody projectQ [us/step] | Simbody Assembler::track [us/step] "
         "| ccma faster than projectQ | ccma faster than track | iterations ccma / projectQ / track "
         "| max EE difference to ccma, projectQ / track [m] | ccma without predictor [us/step] |\n"
      << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const HeadToHeadResult& r : results) {
    out << "| " << r.model << " | " << r.path << " | " << TimeCell(r.ccma) << " | " << TimeCell(r.project_q) << " | "
        << TimeCell(r.assembler_track) << " | " << SpeedUpCell(r.ccma, r.project_q) << " | "
        << SpeedUpCell(r.ccma, r.assembler_track) << " | " << Format("%.0f", Median(r.ccma.iterations)) << " / "
        << Format("%.0f", Median(r.project_q.iterations)) << " / "
        << (r.assembler_run ? Format("%.0f", Median(r.assembler_track.iterations)) : "n/a") << " | "
        << Format("%.1e", r.max_ee_difference_project_q_m) << " / "
        << (r.assembler_run ? Format("%.1e", r.max_ee_difference_track_m) : "n/a")
        << " | " << TimeCell(r.ccma_no_predictor) << " |\n";
  }
  out << "\nThe same run, then each solver alone, all laps in its own loop (its caches warm, as in a program "
         "that runs one solver):\n\n"
      << "| model | path | ccma [us/step] | Simbody projectQ [us/step] | Simbody Assembler::track [us/step] "
         "| ccma faster than projectQ | ccma faster than track |\n"
      << "|---|---|---|---|---|---|---|\n";
  for (const HeadToHeadResult& r : results) {
    out << "| " << r.model << " | " << r.path << " | " << TimeCell(r.ccma_alone) << " | "
        << TimeCell(r.project_q_alone) << " | " << TimeCell(r.assembler_track_alone) << " | "
        << SpeedUpCell(r.ccma_alone, r.project_q_alone) << " | " << SpeedUpCell(r.ccma_alone, r.assembler_track_alone)
        << " |\n";
  }
  out << "\n";
  for (const HeadToHeadResult& r : results) {
    out << "- " << r.model << ", " << r.path << ": ccma state " << r.ccma_state_size << " (" << r.ccma_constraint_rows
        << " constraint rows); Simbody " << r.simbody_free_mobilities << " free mobilities on " << r.simbody_tree_joints
        << " tree joints, " << r.simbody_loop_joints << " loop joints as " << r.simbody_constraint_equations
        << " constraint equations (" << r.assembler_disabled_equations
        << " redundant ones disabled for the Assembler"
        << (r.assembler_run ? std::string() : "; Assembler not run: " + r.assembler_note)
        << "). Failed steps ccma / projectQ / track: " << r.ccma.failures + r.ccma_alone.failures << " / "
        << r.project_q.failures + r.project_q_alone.failures << " / "
        << r.assembler_track.failures + r.assembler_track_alone.failures
        << ". Worst constraint error at a step's end: ccma " << Format("%.1e", r.worst_residual_ccma)
        << " (2-norm), projectQ " << Format("%.1e", r.worst_error_project_q) << ", track "
        << Format("%.1e", r.worst_error_track) << " (largest). ccma's end-effector vs the closed form: "
        << Format("%.1e", r.max_ee_error_ccma_m) << " m.\n";
  }
  return out.str();
}

std::string JsonReport(const Machine& machine, const std::vector<HeadToHeadResult>& results) {
  nlohmann::json models = nlohmann::json::array();
  for (const HeadToHeadResult& r : results) {
    models.push_back({{"model", r.model},
                      {"path", r.path},
                      {"steps_per_lap", r.steps},
                      {"laps", r.laps},
                      {"tolerance", r.tolerance},
                      {"ccma_state_size", r.ccma_state_size},
                      {"ccma_constraint_rows", r.ccma_constraint_rows},
                      {"simbody_free_mobilities", r.simbody_free_mobilities},
                      {"simbody_tree_joints", r.simbody_tree_joints},
                      {"simbody_loop_joints", r.simbody_loop_joints},
                      {"simbody_constraint_equations", r.simbody_constraint_equations},
                      {"assembler_disabled_equations", r.assembler_disabled_equations},
                      {"ccma", SolverJson(r.ccma)},
                      {"ccma_no_predictor", SolverJson(r.ccma_no_predictor)},
                      {"simbody_project_q", SolverJson(r.project_q)},
                      {"simbody_assembler_track", SolverJson(r.assembler_track)},
                      {"alone",
                       {{"ccma", SolverJson(r.ccma_alone)},
                        {"simbody_project_q", SolverJson(r.project_q_alone)},
                        {"simbody_assembler_track", SolverJson(r.assembler_track_alone)},
                        {"ccma_over_project_q", Median(r.ccma_alone.time_us) / Median(r.project_q_alone.time_us)},
                        {"ccma_over_track", r.assembler_run ? nlohmann::json(Median(r.ccma_alone.time_us) /
                                                                             Median(r.assembler_track_alone.time_us))
                                                          : nlohmann::json(nullptr)}}},
                      {"ccma_over_project_q", Median(r.ccma.time_us) / Median(r.project_q.time_us)},
                      {"ccma_over_track", r.assembler_run ? nlohmann::json(Median(r.ccma.time_us) /
                                                                           Median(r.assembler_track.time_us))
                                                        : nlohmann::json(nullptr)},
                      {"assembler_note", r.assembler_note},
                      {"max_ee_difference_project_q_m", r.max_ee_difference_project_q_m},
                      {"max_ee_difference_track_m", r.max_ee_difference_track_m},
                      {"max_ee_error_ccma_m", r.max_ee_error_ccma_m},
                      {"worst_residual_ccma", r.worst_residual_ccma},
                      {"worst_error_project_q", r.worst_error_project_q},
                      {"worst_error_track", r.worst_error_track}});
  }
  const nlohmann::json doc = {{"machine", {{"cpu", machine.cpu}, {"cores", machine.cores}}},
                              {"simbody_version", machine.simbody_version},
                              {"time_unit", "us per step"},
                              {"models", models}};
  return doc.dump(2) + "\n";
}

}  // namespace ccma::simbody_benchmark
