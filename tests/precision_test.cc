// The end-effector's pose covariance from the bases' pose noise
// (analyses/precision.h) against 10,000 Monte Carlo samples: each base's
// x, y and heading drawn with the replay's motion-capture sigmas, the
// mechanism re-solved, the end-effector's pose change measured.
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "analyses/precision.h"
#include "ccma/rotation.h"
#include "formats/model_loader.h"
#include "problems/forward_problem.h"

namespace ccma {
namespace precision_test {

// [p - p0; Log(R R0^T)] (world axes).
Eigen::Matrix<double, 6, 1> PoseChange(const EndEffectorPose& pose, const EndEffectorPose& home) {
  Eigen::Matrix<double, 6, 1> x;
  x.head<3>() = pose.position - home.position;
  x.tail<3>() = QuaternionLog(Eigen::Quaterniond(pose.rotation * home.rotation.transpose()));
  return x;
}

void ExpectCovarianceMatchesMonteCarlo(const std::string& name) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
  const State home = forward.state();
  const Eigen::VectorXd u0 = forward.controls();
  const EndEffectorPose pose0 = forward.end_effector();
  const BasePoseNoise noise;  // 1 mm, 3 mrad
  const Eigen::Matrix<double, 6, 6> analytic = EndEffectorCovariance(model, home, u0, noise);
  ASSERT_TRUE(analytic.allFinite());
  std::mt19937 rng(2026);
  std::normal_distribution<double> position(0.0, noise.position_sigma), heading(0.0, noise.heading_sigma);
  constexpr int kSamples = 10000;
  Eigen::Matrix<double, 6, 6> sampled = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> mean = Eigen::Matrix<double, 6, 1>::Zero();
  for (int i = 0; i < kSamples; ++i) {
    Eigen::VectorXd u = u0;
    for (int k = 0; k < model.num_bases(); ++k) u.segment<3>(3 * k) += Eigen::Vector3d{position(rng), position(rng), heading(rng)};
    forward.SetState(home);
    forward.Solve(u);
    const Eigen::Matrix<double, 6, 1> x = PoseChange(forward.end_effector(), pose0);
    mean += x;
    sampled += x * x.transpose();
  }
  mean /= kSamples;
  sampled = sampled / kSamples - mean * mean.transpose();
  // Sampling error of a variance from 10,000 draws: about sqrt(2/N) = 1.4 %.
  const double scale = analytic.diagonal().maxCoeff();
  EXPECT_LT((sampled - analytic).cwiseAbs().maxCoeff(), 0.05 * scale) << name << "\n" << sampled << "\n\n" << analytic;
  for (int i = 0; i < 6; ++i) {
    if (analytic(i, i) > 1e-3 * scale) EXPECT_NEAR(sampled(i, i) / analytic(i, i), 1.0, 0.05) << name << " " << i;
  }
}

TEST(Precision, CovarianceMatchesMonteCarlo4dofComplete) { ExpectCovarianceMatchesMonteCarlo("4dof_complete"); }
TEST(Precision, CovarianceMatchesMonteCarlo6dofSixAgents) { ExpectCovarianceMatchesMonteCarlo("6dof_six_agents"); }
TEST(Precision, CovarianceMatchesMonteCarlo4dofReduced) { ExpectCovarianceMatchesMonteCarlo("4dof_reduced"); }

TEST(Precision, NoNoiseNoBasesNoCovariance) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/stewart_gough_6ups.yaml");  // no mobile base
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
  EXPECT_EQ(EndEffectorCovariance(model, forward.state(), forward.controls(), {}).cwiseAbs().maxCoeff(), 0.0);
  const Model bases = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_complete.yaml");
  ForwardProblem f2(bases);
  ASSERT_TRUE(f2.Solve(bases.home_controls()).assembled);
  EXPECT_EQ(EndEffectorCovariance(bases, f2.state(), f2.controls(), {0.0, 0.0}).cwiseAbs().maxCoeff(), 0.0);
  // Twice the sigma, four times the covariance.
  const Eigen::Matrix<double, 6, 6> one = EndEffectorCovariance(bases, f2.state(), f2.controls(), {0.001, 0.003});
  const Eigen::Matrix<double, 6, 6> two = EndEffectorCovariance(bases, f2.state(), f2.controls(), {0.002, 0.006});
  EXPECT_LT((two - 4 * one).cwiseAbs().maxCoeff(), 1e-15);
}

}  // namespace
}  // namespace ccma
