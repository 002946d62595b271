// The loaded equilibrium (problems/loaded_equilibrium.h) on generated models
// of every kind (a Stewart-like CCMA, a UPS platform, a platform on
// quadrupeds) from 3 to 50 agents, with stiffness on every joint and every
// base and 1 kg on every body: under loads whose linear deflection is small
// (1e-5 m or rad at most), the nonlinear equilibrium converges, by the sparse
// Newton path and by the dense one, and lies within 1 % of the linear answer
// of `ccma statics`; at a tenth of the loads the gap is about a tenth
// (the difference is the mechanism's nonlinearity, not the solver's error).
//
// Before the loaded equilibrium's tolerances followed the springs' rounding
// (problems/internal/loaded_tolerances.h) and its idle regulariser lay far
// below the softest resisted motion (kKktIdleStiffness), every one of these
// failed: "the springs held 0 % of the loads".
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analyses/statics.h"
#include "ccma/loads.h"
#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "problems/forward_problem.h"
#include "problems/loaded_equilibrium.h"

namespace ccma {
namespace loaded_generated_models_test {

struct Case {
  const char* kind;  // ccma, stewart_gough, legged
  int agents;
};

std::string CaseName(const ::testing::TestParamInfo<Case>& info) {
  return std::string(info.param.kind) + "_" + std::to_string(info.param.agents);
}

std::string Generated(const Case& c) {
  const std::string kind = c.kind;
  if (kind == "legged") {
    LeggedOptions options;
    options.agents = c.agents;
    return GenerateLeggedModel(options);
  }
  StewartOptions options;
  options.agents = c.agents;
  return kind == "ccma" ? GenerateStewartModel(options) : GenerateStewartGoughModel(options);
}

// Stiffness on every base (its x, y, heading) and in every direction of every
// joint (its motor too), 1 kg on every body; `g` scales gravity.
Model CompliantEverywhere(const Case& c, double g) {
  Model model = LoadModelFromString(Generated(c), std::string(c.kind) + ".yaml");
  for (MobileBase& base : model.mobile_bases) base.stiffness.k = Eigen::Vector3d(1e5, 1e5, 1e3);
  for (Body& body : model.bodies) body.inertia.mass = 1.0;
  for (Joint& joint : model.joints) {
    joint.stiffness.translation.assign(static_cast<size_t>(TranslationSpringCount(joint.type)), 1e7);
    joint.stiffness.rotation.assign(static_cast<size_t>(RotationSpringCount(joint.type)), 1e4);
    if (joint.actuated) joint.stiffness.axis = 1e5;
  }
  model.gravity = Eigen::Vector3d(0, 0, -9.81 * g);
  return model;
}

// The largest component of a deflection [m or rad].
double Size(const Eigen::Matrix<double, 6, 1>& d) { return d.cwiseAbs().maxCoeff(); }

class LoadedGenerated : public ::testing::TestWithParam<Case> {};

TEST_P(LoadedGenerated, SmallLoadsConvergeToTheLinearDeflection) {
  ExternalWrench w;
  w.force = Eigen::Vector3d(1, 0.5, -1);
  w.moment = Eigen::Vector3d(0.05, -0.02, 0.03);
  // Scale the loads so that the linear deflection is 1e-5 (m or rad).
  double scale = 1;
  {
    const Model unit = CompliantEverywhere(GetParam(), 1.0);
    ForwardProblem forward(unit);
    ASSERT_TRUE(forward.Solve(unit.home_controls()).assembled);
    scale = 1e-5 / Size(ComputeStatics(unit, forward.state(), forward.controls(), w).compliance.deflection);
  }
  w.force *= scale;
  w.moment *= scale;
  const Model model = CompliantEverywhere(GetParam(), scale);
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
  double last_gap = 0;
  for (const double fraction : {1.0, 0.1}) {
    Model scaled = model;
    scaled.gravity *= fraction;
    ExternalWrench wf = w;
    wf.force *= fraction;
    wf.moment *= fraction;
    const Eigen::Matrix<double, 6, 1> linear =
        ComputeStatics(scaled, forward.state(), forward.controls(), wf).compliance.deflection;
    for (const bool sparse : {true, false}) {
      if (!sparse && GetParam().agents > 6) continue;  // the dense path is O(N^3): the small models
      LoadedOptions options;
      options.sparse = sparse;
      const LoadedEquilibrium r = SolveLoadedEquilibrium(scaled, forward.state(), forward.controls(), wf, options);
      ASSERT_TRUE(r.converged) << (sparse ? "sparse: " : "dense: ") << r.message;
      EXPECT_TRUE(r.held);
      EXPECT_DOUBLE_EQ(r.load_fraction, 1.0);
      const double gap = Size(r.deflection - linear) / Size(linear);
      EXPECT_LT(gap, 0.01) << "fraction " << fraction << (sparse ? " sparse" : " dense");
      if (sparse && fraction == 1.0) last_gap = gap;
      if (sparse && fraction == 0.1) EXPECT_LT(gap, 0.2 * last_gap + 1e-6) << "the gap shrinks with the loads";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Generated, LoadedGenerated,
                         ::testing::Values(Case{"ccma", 3}, Case{"ccma", 4}, Case{"ccma", 5}, Case{"ccma", 8},
                                         Case{"ccma", 20}, Case{"ccma", 50}, Case{"stewart_gough", 6},
                                         Case{"stewart_gough", 9}, Case{"stewart_gough", 20},
                                         Case{"stewart_gough", 50}, Case{"legged", 3}, Case{"legged", 4},
                                         Case{"legged", 6}, Case{"legged", 12}, Case{"legged", 50}),
                         CaseName);

}  // namespace loaded_generated_models_test
}  // namespace ccma
