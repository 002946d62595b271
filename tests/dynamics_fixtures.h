// Models with masses and smooth control paths for the inverse dynamics
// tests (tests/dynamics_test.cc, tests/dalembert_test.cc).
#ifndef CCMA_TESTS_DYNAMICS_FIXTURES_H_
#define CCMA_TESTS_DYNAMICS_FIXTURES_H_

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "analyses/dynamics.h"
#include "ccma/ccma.h"
#include "problems/forward_problem.h"

namespace ccma::testing {

// Seeded masses, centres and physical inertias on every body, and a payload.
inline Model WithMasses(Model model, int seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1, 1);
  for (Body& body : model.bodies) {
    body.inertia.mass = 1.25 + 0.75 * d(rng);
    body.inertia.com_B = Eigen::Vector3d{0.05 * d(rng), 0.05 * d(rng), 0.05 * d(rng)};
    const Eigen::Vector3d moments{0.02 + 0.01 * d(rng), 0.02 + 0.01 * d(rng), 0.02 + 0.01 * d(rng)};
    const Eigen::Matrix3d R = Eigen::AngleAxisd(3 * d(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                              Eigen::AngleAxisd(3 * d(rng), Eigen::Vector3d::UnitX()).toRotationMatrix();
    body.inertia.inertia_B = R * moments.asDiagonal() * R.transpose();  // principal moments within the triangle
  }
  model.end_effector.payload.mass = 2.0;
  model.end_effector.payload.com_B = Eigen::Vector3d(0.01, -0.02, 0.05);
  return model;
}

// Every control as a sine about home, seeded amplitudes (0.04) and phases,
// one period over `duration` s, with its exact rates and accelerations.
struct SineControls {
  SineControls(const Model& model, int seed, double duration_s) : home(model.home_controls()), duration(duration_s) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> d(-1, 1);
    amplitude.resize(home.size());
    phase.resize(home.size());
    for (Eigen::Index i = 0; i < home.size(); ++i) amplitude[i] = 0.04 * d(rng);
    for (Eigen::Index i = 0; i < home.size(); ++i) phase[i] = 3 * d(rng);
  }
  double w() const { return 2 * M_PI / duration; }
  Eigen::VectorXd U(double t) const {
    return home + amplitude.cwiseProduct((phase.array() + w() * t).sin().matrix());
  }
  Eigen::VectorXd Rate(double t) const {
    return w() * amplitude.cwiseProduct((phase.array() + w() * t).cos().matrix());
  }
  Eigen::VectorXd Acceleration(double t) const { return -w() * w() * (U(t) - home); }

  Eigen::VectorXd home, amplitude, phase;
  double duration;
};

// SineControls sampled at `rows` rows over `duration` s, when every row
// assembles; empty when the controls are tied (over-actuated models).
inline ControlPath SinePath(const Model& model, int seed, int rows, double duration) {
  const SineControls sine(model, seed, duration);
  ControlPath path;
  path.source = "sine";
  ForwardProblem forward(model);
  for (int r = 0; r < rows; ++r) {
    const double t = duration * r / (rows - 1);
    const Eigen::VectorXd u = sine.U(t);
    if (!forward.Assemble(u).assembled) return {};
    path.times.push_back(t);
    path.controls.push_back(u);
  }
  return path;
}

}  // namespace ccma::testing

#endif  // CCMA_TESTS_DYNAMICS_FIXTURES_H_
