// Kinematic control: targets reached exactly on every reference model and
// checked by re-assembling the returned controls from home; the bundled
// paths; honest failure; least-norm control changes for redundant systems.
#include <fstream>
#include <random>
#include <unistd.h>
#include <string>

#include <gtest/gtest.h>

#include "formats/model_loader.h"
#include "ccma/rotation.h"
#include "formats/waypoints.h"
#include "problems/control_problem.h"
#include "problems/internal/end_effector_error.h"
#include "problems/trajectory.h"
#include "ccma/internal/dense_factorizations.h"
#include "tests/tool_run.h"

namespace ccma {
namespace control_test {

Model LoadReference(const std::string& name) {
  return LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
}

// A seeded target within 5 cm and 0.1 rad of home (yaw only for 4-DOF).
PoseTarget SeededTarget(const Model& m, std::mt19937& rng) {
  std::normal_distribution<double> n;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d direction = Eigen::Vector3d{n(rng), n(rng), n(rng)}.normalized();
  PoseTarget t;
  t.position = m.end_effector.p_W_home + 0.05 * unit(rng) * direction;
  if (m.end_effector.controlled[kRoll]) {
    const Eigen::Vector3d axis = Eigen::Vector3d{n(rng), n(rng), n(rng)}.normalized();
    t.rpy = RpyFromRotation(QuaternionExp(0.1 * unit(rng) * axis).toRotationMatrix());
  } else {
    t.rpy = Eigen::Vector3d(0, 0, 0.1 * (2 * unit(rng) - 1));
  }
  return t;
}

// Largest error over the controlled components of an end-effector pose.
double ControlledError(const Model& m, const EndEffectorPose& pose, const PoseTarget& t) {
  double error = 0;
  for (int k = 0; k < 3; ++k) {
    if (m.end_effector.controlled[k]) error = std::max(error, std::abs(pose.position[k] - t.position[k]));
  }
  if (m.end_effector.controlled[kRoll]) {
    const Eigen::Matrix3d R_t = RotationFromRpy(t.rpy);
    error = std::max(error, QuaternionLog(Eigen::Quaterniond(pose.rotation * R_t.transpose())).norm());
  } else if (m.end_effector.controlled[kYaw]) {
    error = std::max(error, std::abs(WrapAngle(pose.rpy.z() - t.rpy.z())));
  }
  return error;
}

struct Case {
  std::string model;
  ControlMethod method;
  int targets;
};
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.model << (c.method == ControlMethod::kBfgs ? " bfgs" : " lm");
}

class ControlReachesTargets : public ::testing::TestWithParam<Case> {};

TEST_P(ControlReachesTargets, WithinOneNanometreAndReassembledFromHome) {
  const Model m = LoadReference(GetParam().model);
  ControlOptions options;
  options.method = GetParam().method;
  for (int seed = 0; seed < GetParam().targets; ++seed) {
    std::mt19937 rng(seed);
    const PoseTarget target = SeededTarget(m, rng);
    ControlProblem control(m, options);
    const ControlResult r = control.MoveTo(target);
    ASSERT_TRUE(r.converged) << GetParam().model << " seed " << seed << ": " << r.warning;
    EXPECT_LE(r.error, 1e-9);
    EXPECT_LT(r.residual_energy, 1e-20);
    EXPECT_LT(r.max_step_residual_energy, 1e-16);
    EXPECT_LE(ControlledError(m, control.forward().end_effector(), target), 1e-9);
    // Reduced bases keep their heading; nothing else is touched.
    for (int k = 0; k < m.num_bases(); ++k) {
      if (m.mobile_bases[k].actuation == Actuation::kReduced) {
        EXPECT_EQ(control.controls()[3 * k + 2], m.mobile_bases[k].home_pose.z());
      }
    }
    // An independent assembly of the returned controls, from home.
    ForwardProblem check(m);
    const ForwardResult assembled = check.Assemble(control.controls());
    EXPECT_TRUE(assembled.assembled) << assembled.residual_energy;
    EXPECT_LE(ControlledError(m, check.end_effector(), target), 1e-9) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(
    FiveReferenceModels, ControlReachesTargets,
    ::testing::Values(Case{"4dof_reduced", ControlMethod::kLevenbergMarquardt, 20},
                      Case{"4dof_complete", ControlMethod::kLevenbergMarquardt, 20},
                      Case{"6dof_symmetric", ControlMethod::kLevenbergMarquardt, 20},
                      Case{"6dof_asymmetric", ControlMethod::kLevenbergMarquardt, 20},
                      Case{"6dof_six_agents", ControlMethod::kLevenbergMarquardt, 20},
                      Case{"4dof_reduced", ControlMethod::kBfgs, 3},
                      Case{"6dof_asymmetric", ControlMethod::kBfgs, 3},
                      Case{"6dof_six_agents", ControlMethod::kBfgs, 3}),
    [](const auto& info) {
      return info.param.model + (info.param.method == ControlMethod::kBfgs ? "_bfgs" : "_lm");
    });

class BundledPaths : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(BundledPaths, EveryStepStaysAssembled) {
  const auto& [model, path] = GetParam();
  const Model m = LoadReference(model);
  const auto waypoints = LoadWaypoints(std::string(CCMA_MODELS_DIR) + "/paths/" + path + ".csv");
  ControlProblem control(m);
  int steps = 0;
  const TrajectoryResult r = FollowWaypoints(control, waypoints, [&](const TrajectoryStep& s) {
    ++steps;
    EXPECT_TRUE(s.result.reached) << "t = " << s.time;
    EXPECT_LT(s.result.residual_energy, 1e-16) << "t = " << s.time;
  });
  EXPECT_TRUE(r.converged) << r.warning;
  EXPECT_GT(steps, 100);
  EXPECT_LT(r.max_residual_energy, 1e-16);
  EXPECT_LE(r.max_error, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(PaperExperiments, BundledPaths,
                         ::testing::Combine(::testing::Values("4dof_reduced", "4dof_complete"),
                                            ::testing::Values("4dof_sequential", "4dof_combined")));

TEST(Control, UnreachableTargetIsReportedWithTheBestControls) {
  for (const std::string name : {"4dof_reduced", "6dof_symmetric"}) {
    const Model m = LoadReference(name);
    ControlProblem control(m);
    PoseTarget target = control.CurrentPose();
    target.position.z() += 0.6;  // far above what the legs reach
    const ControlResult r = control.MoveTo(target);
    EXPECT_FALSE(r.converged) << name;
    EXPECT_FALSE(r.warning.empty());
    EXPECT_GT(r.error, 0.05);
    // The best controls found are returned with their residual, assembled
    // where the legs are stretched as far as they go.
    EXPECT_TRUE(std::isfinite(r.residual_energy));
    EXPECT_GT(control.forward().end_effector().position.z(), m.end_effector.p_W_home.z() + 0.05);
  }
}

TEST(Control, ConditioningFiguresAnnounceTheWorkspaceBoundary) {
  // Lifting the end-effector of 6dof_symmetric straightens its legs (full
  // stretch near z = 0.85 m): the smallest singular value of dX/du falls
  // steadily towards 0 while every step is still reached.
  const Model m = LoadReference("6dof_symmetric");
  ControlProblem control(m);
  double first = 0, previous = 0;
  for (double z = 0.60; z <= 0.845; z += 0.02) {
    PoseTarget target = control.CurrentPose();
    target.position.z() = z;
    const ControlResult r = control.MoveTo(target);
    ASSERT_TRUE(r.converged) << "z = " << z;
    EXPECT_GT(r.rcond, 0.0);
    if (first == 0) first = r.min_singular_value_dX_du;
    if (z > 0.7) EXPECT_LT(r.min_singular_value_dX_du, previous) << "z = " << z;
    previous = r.min_singular_value_dX_du;
  }
  EXPECT_GT(first, 0.5);
  EXPECT_LT(previous, 0.25 * first);
}

TEST(Control, RedundantControlsChangeByTheLeastNorm) {
  // 6dof_symmetric: 9 controls for 6 end-effector DOF. To first order the
  // change must lie in the row space of dX/du: no motion in the 3 redundant
  // directions, which would move bases without moving the end-effector.
  const Model m = LoadReference("6dof_symmetric");
  ControlProblem control(m);
  const Eigen::MatrixXd ds_du = control.StateSensitivity();
  EndEffectorError error(m);
  Eigen::VectorXd e;
  Eigen::MatrixXd de_ds;
  const PoseTarget home = control.CurrentPose();
  error.Evaluate(control.forward().state(), home, &e, &de_ds);
  const Eigen::MatrixXd dX_du = de_ds * ds_du;  // 6 x 9
  const JacobiSvd svd(dX_du, Eigen::ComputeFullV);
  const Eigen::MatrixXd null_space = svd.matrixV().rightCols(3);
  EXPECT_LT(svd.singularValues()[5], 1e6);

  PoseTarget target = home;
  target.position += Eigen::Vector3d(0.004, -0.003, 0.002);
  target.rpy += Eigen::Vector3d(0.002, 0.001, -0.002);
  const Eigen::VectorXd u0 = control.controls();
  ASSERT_TRUE(control.SolveStep(target).reached);
  const Eigen::VectorXd du = control.controls() - u0;
  EXPECT_GT(du.norm(), 1e-3);
  EXPECT_LT((null_space.transpose() * du).norm(), 0.02 * du.norm());
}

TEST(Control, FiniteDifferenceGradientsReachTheSameControls) {
  for (const std::string name : {"4dof_reduced", "6dof_asymmetric"}) {
    const Model m = LoadReference(name);
    ControlOptions fd_options;
    fd_options.gradient = GradientMethod::kFiniteDifference;
    ControlProblem analytic(m), fd(m, fd_options);
    PoseTarget target = analytic.CurrentPose();
    target.position += Eigen::Vector3d(0.006, 0.004, -0.005);
    target.rpy.z() += 0.004;
    const ControlStepResult a = analytic.SolveStep(target);
    const ControlStepResult b = fd.SolveStep(target);
    EXPECT_TRUE(a.reached);
    EXPECT_TRUE(b.reached);
    EXPECT_LT((analytic.controls() - fd.controls()).lpNorm<Eigen::Infinity>(), 1e-6) << name;
    EXPECT_GT(b.forward_solves, 2 * static_cast<int>(analytic.effective_controls().size()));
  }
}

TEST(Waypoints, MalformedFilesNameTheLine) {
  const std::string path = ccma::testing::TestDir() + "/" + std::to_string(getpid()) + "_bad.csv";
  auto error_of = [&](const std::string& text) {
    std::ofstream(path) << text;
    try {
      LoadWaypoints(path);
    } catch (const WaypointError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string header = "time,x,y,z,roll,pitch,yaw\n";
  EXPECT_NE(error_of("t,x,y\n").find(":1: the header"), std::string::npos);
  EXPECT_NE(error_of(header + "0,0,0,0.6,0,0\n").find(":2: expected 7 values"), std::string::npos);
  EXPECT_NE(error_of(header + "0,0,0,0.6,0,0,nan\n").find(":2: 'nan'"), std::string::npos);
  EXPECT_NE(error_of(header + "1,0,0,0.6,0,0,0\n0,0,0,0.6,0,0,0\n").find(":3: time goes"),
            std::string::npos);
  EXPECT_NE(error_of(header).find("no waypoints"), std::string::npos);
  EXPECT_THROW(LoadWaypoints("/nonexistent.csv"), WaypointError);
}

}  // namespace
}  // namespace ccma
