// The cost of clearance in a control step (model_format.md, "Collision
// geometry and obstacles"): one paper-size step (10 mm + 0.005 rad, as
// control_benchmark.cc) without collision geometry, then with the bases as
// cylinders and 0, 5 and 20 pillars around the mechanism (seeded, none
// touching the bases at home), on 4dof_reduced, 6dof_six_agents and a
// generated 48-agent model. Each iteration alternates between the home pose
// and the moved pose.
//   build/benchmarks/clearance_benchmark --benchmark_repetitions=5 \
//       --benchmark_report_aggregates_only=true
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "ccma/ccma.h"
#include "benchmarks/paper_step.h"

namespace {

using namespace ccma;

std::string ModelText(const std::string& name) {
  if (name == "generated_48") {
    StewartOptions options;
    options.agents = 48;
    options.base_radius = 3.0;  // 0.39 m between neighbouring bases
    return GenerateStewartModel(options);
  }
  std::ifstream in(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// `obstacles` pillars (radius 0.1 m) on a ring outside the bases, seeded.
std::string WithCollision(const std::string& text, double ring, double base_radius, int obstacles) {
  std::ostringstream out;
  out << text << "\ncollision: {margin: 0.02, base_radius: " << base_radius << "}\nobstacles:";
  if (obstacles == 0) out << " []";
  out << "\n";
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), radial(ring + 0.3, ring + 1.0);
  for (int i = 0; i < obstacles; ++i) {
    const double a = angle(rng), r = radial(rng);
    out << "  - {name: pillar" << i << ", cylinder: {center: [" << r * std::cos(a) << ", " << r * std::sin(a)
        << "], radius: 0.1, height: 1.0}}\n";
  }
  return out.str();
}


// obstacles < 0: no collision geometry at all.
void BM_ClearanceStep(benchmark::State& state, const std::string& name, double ring, double base_radius,
                      int obstacles) {
  const std::string text = ModelText(name);
  const Model model =
      LoadModelFromString(obstacles < 0 ? text : WithCollision(text, ring, base_radius, obstacles), name);
  ControlProblem control(model);
  const double reached_fraction = TimePaperStepsOutAndBack(state, &control);
  state.counters["reached_fraction"] = reached_fraction;
  state.counters["shapes"] = model.collision.enabled ? model.num_bases() + obstacles : 0;
}

int Register() {
  struct Case {
    std::string model;
    double ring, base_radius;
  };
  for (const Case& c : {Case{"4dof_reduced", 0.7, 0.3}, Case{"6dof_six_agents", 0.7, 0.1},
                        Case{"generated_48", 3.1, 0.15}}) {
    for (int obstacles : {-1, 0, 5, 20}) {
      const std::string label = obstacles < 0 ? "off" : std::to_string(obstacles);
      benchmark::RegisterBenchmark(("ClearanceStep/" + c.model + "/" + label).c_str(), BM_ClearanceStep, c.model,
                                   c.ring, c.base_radius, obstacles)
          ->Unit(benchmark::kMillisecond);
    }
  }
  return 0;
}

const int kRegistered = Register();

}  // namespace

BENCHMARK_MAIN();
