// ccma against Simbody on the same warm path (issue 11, item 3), interleaved
// step by step and then each solver alone (head_to_head.h): prints Markdown
// tables on stdout and, with --json=FILE, writes the same as JSON.
//   simbody_benchmark [--laps=10] [--models=4dof_reduced,6dof_six_agents]
//                     [--paths=horizontal,vertical] [--json=FILE]
// Built only when CMake finds Simbody (benchmarks/CMakeLists.txt); run by
// scripts/simbody_bench.sh. Timings only: it asserts nothing about speed,
// but exits 1 when a solver fails a step or the end-effectors disagree by
// more than 1e-9 m, since then the times would not compare like with like.
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/simbody/head_to_head.h"
#include "benchmarks/simbody/report.h"
#include "formats/model_loader.h"

namespace {

constexpr double kMaxEndEffectorDifference = 1e-9;  // m

std::vector<std::string> Split(const std::string& list) {
  std::vector<std::string> items;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace ccma::simbody_benchmark;
  HeadToHeadOptions options;
  std::vector<std::string> models = {"4dof_reduced", "6dof_six_agents"};
  std::vector<std::string> paths = {"horizontal", "vertical"};
  std::string json_path;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--laps=", 0) == 0) {
      options.laps = std::atoi(arg.c_str() + 7);
    } else if (arg.rfind("--models=", 0) == 0) {
      models = Split(arg.substr(9));
    } else if (arg.rfind("--paths=", 0) == 0) {
      paths = Split(arg.substr(8));
    } else if (arg.rfind("--json=", 0) == 0) {
      json_path = arg.substr(7);
    } else {
      std::cerr << "usage: simbody_benchmark [--laps=N] [--models=a,b] [--paths=horizontal,vertical] [--json=FILE]\n";
      return 2;
    }
  }
  std::vector<CirclePlane> planes;
  for (const std::string& path : paths) {
    if (path == "horizontal") planes.push_back(CirclePlane::kHorizontal);
    else if (path == "vertical") planes.push_back(CirclePlane::kVertical);
    else {
      std::cerr << "simbody_benchmark: unknown path '" << path << "' (horizontal, vertical)\n";
      return 2;
    }
  }
  if (options.laps < 1 || models.empty() || planes.empty()) {
    std::cerr << "simbody_benchmark: --laps must be >= 1, --models and --paths non-empty\n";
    return 2;
  }

  std::vector<HeadToHeadResult> results;
  bool agreed = true;
  try {
    for (const std::string& name : models) {
      const ccma::Model model = ccma::LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
      for (const CirclePlane plane : planes) {
        options.plane = plane;
        std::cerr << "simbody_benchmark: " << name << ", " << CirclePlaneName(plane) << " circle, "
                  << options.laps << " laps of " << options.steps << " steps\n";
        results.push_back(RunHeadToHead(model, options));
        const HeadToHeadResult& r = results.back();
        const int failures = r.ccma.failures + r.project_q.failures + r.assembler_track.failures +
                             r.ccma_alone.failures + r.project_q_alone.failures + r.assembler_track_alone.failures;
        if (failures > 0 || r.max_ee_difference_project_q_m > kMaxEndEffectorDifference ||
            r.max_ee_difference_track_m > kMaxEndEffectorDifference) {
          std::cerr << "simbody_benchmark: " << name << ", " << r.path << ": " << failures
                    << " failed steps or end-effectors more than 1e-9 m apart (see the table)\n";
          agreed = false;
        }
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "simbody_benchmark: " << e.what() << "\n";
    return 1;
  }

  const Machine machine = DescribeMachine();
  std::cout << MarkdownReport(machine, results);
  if (!json_path.empty()) {
    std::ofstream json(json_path);
    json << JsonReport(machine, results);
    if (!json) {
      std::cerr << "simbody_benchmark: cannot write " << json_path << "\n";
      return 1;
    }
  }
  return agreed ? 0 : 1;
}
