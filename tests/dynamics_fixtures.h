// Models with masses and smooth control paths for the inverse dynamics
// tests (tests/dynamics_test.cc, tests/dalembert_test.cc).
#ifndef CCMA_TESTS_DYNAMICS_FIXTURES_H_
#define CCMA_TESTS_DYNAMICS_FIXTURES_H_

#include <cmath>
#include <random>
#include <vector>

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

// The rows ControlProblem::FollowWaypoints makes along a loop of the
// end-effector about its home position (x = r sin, y = r (1 - cos),
// z = r/2 sin over `duration` s, one waypoint per 50 ms), as ccma
// trajectory writes them, on the second of two laps (the first turns
// differential bases towards their travel, in place). Controls that
// over-actuated models tie stay consistent: the smooth path of a model whose
// controls a sine cannot move. Control steps of at most max_step_m [m] (and
// half that in rad); empty when some waypoint is not reached. `vertical`:
// z = r sin alone (radial bases move along their headings, no turning).
inline ControlPath FollowedPath(const Model& model, double radius, double duration, double max_step_m,
                                bool vertical = false) {
  ControlOptions options;
  options.max_step_m = max_step_m;
  options.max_step_rad = max_step_m / 2;
  ControlProblem control(model, options);
  const Eigen::Vector3d p0 = control.CurrentPose().position;
  std::vector<Waypoint> waypoints;
  const int n = static_cast<int>(std::lround(duration / 0.05));
  for (int i = 0; i <= 2 * n; ++i) {
    const double t = duration * i / n, a = 2 * M_PI * t / duration;
    Waypoint w;
    w.time = t;
    w.position = p0 + radius * (vertical ? Eigen::Vector3d(0, 0, std::sin(a))
                                         : Eigen::Vector3d(std::sin(a), 1 - std::cos(a), 0.5 * std::sin(a)));
    w.rpy = control.CurrentPose().rpy;
    waypoints.push_back(w);
  }
  ControlPath path;
  path.source = "followed";
  const TrajectoryResult r = FollowWaypoints(control, waypoints, [&](const TrajectoryStep& step) {
    if (step.time < duration) return;  // the first lap
    if (!path.times.empty() && step.time <= path.times.back()) return;  // one row per time
    path.times.push_back(step.time);
    path.controls.push_back(step.controls);
  });
  return r.converged ? path : ControlPath{};
}

}  // namespace ccma::testing

#endif  // CCMA_TESTS_DYNAMICS_FIXTURES_H_
