#include "viewer/deflection_shape.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "ccma/rotation.h"

namespace ccma::viewer {
namespace {

// The points whose displacement measures body b's deflection, in b's frame:
// its origin, its joint points and the end-effector point on its body.
std::vector<Eigen::Vector3d> DeflectionBodyPoints(const Model& model, int b) {
  std::vector<Eigen::Vector3d> points = {Eigen::Vector3d::Zero()};
  for (const Joint& j : model.joints) {
    if (j.body_a == b) points.push_back(j.p_A);
    if (j.body_b == b) points.push_back(j.p_B);
  }
  if (model.end_effector.body == b) points.push_back(model.end_effector.p_B);
  return points;
}

// The largest displacement of body b's points from `rigid` to `loaded` [m].
double DeflectionOfBody(const Model& model, const State& rigid, const State& loaded, int b) {
  const Eigen::Matrix3d R0 = rigid.R_WB(b), R1 = loaded.R_WB(b);
  const Eigen::Vector3d p0 = rigid.p_WB(b), p1 = loaded.p_WB(b);
  double largest = 0;
  for (const Eigen::Vector3d& x_B : DeflectionBodyPoints(model, b)) {
    largest = std::max(largest, ((p1 + R1 * x_B) - (p0 + R0 * x_B)).norm());
  }
  return largest;
}

}  // namespace

DeflectedShape ComputeDeflectedShape(const Model& model, const State& rigid, const Eigen::VectorXd& u,
                                     const DeflectionRequest& request) {
  if (!(request.scale > 0 && request.scale <= kMaxDeflectionScale)) {
    throw DeflectionError("the scale must be a number in (0, 1e6]");
  }
  DeflectedShape shape;
  shape.scale = request.scale;
  try {
    shape.equilibrium = SolveLoadedEquilibrium(model, rigid, u, request.wrench);
  } catch (const std::invalid_argument& e) {
    throw DeflectionError(e.what());
  }
  const State& loaded = shape.equilibrium.state;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const Eigen::Quaterniond q0 = rigid.q_WB(b);
    // The rotation from the rigid pose to the loaded one, world axes, scaled.
    const Eigen::Vector3d turn = QuaternionLog(loaded.q_WB(b) * q0.conjugate());
    shape.q_WB_drawn.push_back((QuaternionExp(request.scale * turn) * q0).normalized());
    shape.p_WB_drawn.push_back(rigid.p_WB(b) + request.scale * (loaded.p_WB(b) - rigid.p_WB(b)));
    const double d = DeflectionOfBody(model, rigid, loaded, b);
    shape.body_deflection_m.push_back(d);
    if (d > shape.max_deflection_m) {
      shape.max_deflection_m = d;
      shape.max_body = b;
    }
  }
  return shape;
}

}  // namespace ccma::viewer
