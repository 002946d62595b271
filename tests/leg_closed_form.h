// Closed-form base poses for the reference models' legs (test oracle).
//
// Given an end-effector pose (p*, R*) and, where the leg leaves it free, a
// base heading change or a position on the base's circle, each base pose
// follows from the geometry alone (no solver):
//  * FRR (complete base, planar R-R leg, 4dof_complete) and RRR (reduced,
//    4dof_reduced): the link's two axes stay parallel, so the leg's plane
//    turns with the end-effector's yaw; the post top P lies on the line
//    (a - P).w = 0 at distance L from the attachment point a.
//  * FRS (complete base, R-S leg, 6dof_*): the same line-circle problem with
//    a chosen heading change dtheta of the base.
//  * RRS (reduced base, R-R-S leg, 6dof_six_agents): the post turns freely,
//    so P is anywhere on a circle around a; a chosen angle picks the point.
//  * FRRU (complete base, R-R-U leg, 6dof_asymmetric leg 2): the universal
//    joint's link axis must be perpendicular to the end-effector axis, which
//    fixes the distal link's angle about the leg axis; then as FRS.
// Everything is read from the Model (joint points and axes at home), so a
// model file with other numbers but these leg shapes works too.
#ifndef CCMA_TESTS_LEG_CLOSED_FORM_H_
#define CCMA_TESTS_LEG_CLOSED_FORM_H_

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "ccma/model.h"
#include "ccma/rotation.h"

namespace ccma::testing {

struct JointAtHome {
  const Joint* joint;
  Eigen::Vector3d point_W;  // at home
  Eigen::Vector3d axis_W;   // revolute / universal first axis, at home
  Eigen::Vector3d axis2_W;  // universal second axis, at home
};

struct Leg {
  int base = -1;
  std::string shape;  // joint letters from base to end-effector: "FRS", ...
  std::vector<JointAtHome> joints;
};

inline JointAtHome AtHome(const Model& m, const Joint& j) {
  const Body& A = m.bodies[j.body_a];
  const Body& B = m.bodies[j.body_b];
  return {&j, A.R_WB_home * j.p_A + A.p_WB_home, A.R_WB_home * j.a_A, B.R_WB_home * j.b_B};
}

// Splits the joints into legs: a leg starts at a joint touching a base and
// runs, in file order, to the joint touching the end-effector body.
inline std::vector<Leg> FindLegs(const Model& m) {
  std::vector<Leg> legs;
  Leg current;
  for (const Joint& j : m.joints) {
    const bool at_base = m.bodies[j.body_a].is_mobile_base() || m.bodies[j.body_b].is_mobile_base();
    if (at_base) {
      current = Leg();
      current.base = m.bodies[j.body_a].is_mobile_base() ? m.bodies[j.body_a].base_index
                                                         : m.bodies[j.body_b].base_index;
    }
    const char letter = j.type == JointType::kFixed       ? 'F'
                        : j.type == JointType::kRevolute  ? 'R'
                        : j.type == JointType::kSpherical ? 'S'
                        : j.type == JointType::kUniversal ? 'U'
                                                          : 'P';
    current.shape += letter;
    current.joints.push_back(AtHome(m, j));
    if (j.body_a == m.end_effector.body || j.body_b == m.end_effector.body) legs.push_back(current);
  }
  return legs;
}

// The point P with P.z = z, (a - P).w = h and |a - P| = L, on the side of
// the leg's home solution (home_offset = P_home - a_home, horizontal part).
// h, the offset of a along the leg axis, is kept from home: the model files'
// 9-digit numbers leave it at ~1e-10 m, not exactly zero.
inline Eigen::Vector3d LineCircle(const Eigen::Vector3d& a, const Eigen::Vector3d& w, double h,
                                  double z, double L, const Eigen::Vector2d& home_offset) {
  const Eigen::Vector2d w_xy(w.x(), w.y());
  const double w_norm = w_xy.norm();
  if (w_norm < 1e-12) throw std::runtime_error("leg axis is vertical: not a planar leg");
  const Eigen::Vector2d n = w_xy / w_norm, t(-n.y(), n.x());
  const double c = ((a.z() - z) * w.z() - h) / w_norm;  // v.n for v = P_xy - a_xy
  const double rho_sq = L * L - (a.z() - z) * (a.z() - z) - c * c;
  if (rho_sq < 0) throw std::runtime_error("end-effector pose out of the leg's reach");
  double s = std::sqrt(rho_sq);
  if (home_offset.dot(t) < 0) s = -s;
  const Eigen::Vector2d v = c * n + s * t;
  return {a.x() + v.x(), a.y() + v.y(), z};
}

// Base pose (x, y, theta) that puts the end-effector at (p_EE, R_EE).
// `free_parameter`: dtheta of a complete base (FRS, FRRU), or the angle
// offset on the circle (RRS); ignored by FRR / RRR.
inline Eigen::Vector3d BasePoseForLeg(const Model& m, const Leg& leg, const Eigen::Vector3d& p_EE,
                                      const Eigen::Matrix3d& R_EE, double free_parameter) {
  const MobileBase& base = m.mobile_bases[leg.base];
  const Eigen::Vector3d B_home(base.home_pose.x(), base.home_pose.y(), 0.0);
  const Eigen::Vector3d p_EE_home = m.end_effector.p_W_home;
  auto on_ee = [&](const Eigen::Vector3d& x_home) { return p_EE + R_EE * (x_home - p_EE_home); };
  const JointAtHome& last = leg.joints.back();
  const Eigen::Vector3d a = on_ee(last.point_W);

  if (leg.shape == "FRR" || leg.shape == "RRR" || leg.shape == "FRS") {
    const JointAtHome& post = leg.joints[1];  // revolute at the post's top
    const double L = (last.point_W - post.point_W).norm();
    const Eigen::Vector3d o = post.point_W - B_home;  // post top from base centre
    double dtheta = free_parameter;
    if (leg.shape != "FRS") {
      // The two axes stay parallel: the leg plane turns with the EE's yaw.
      const Eigen::Vector3d w_now = R_EE * last.axis_W;
      dtheta = WrapAngle(std::atan2(w_now.y(), w_now.x()) -
                         std::atan2(post.axis_W.y(), post.axis_W.x()));
    }
    const Eigen::Matrix3d Rz = RotationZ(dtheta);
    const Eigen::Vector3d w = Rz * post.axis_W;
    const Eigen::Vector2d home_offset = (post.point_W - last.point_W).head<2>();
    const Eigen::Vector2d home_offset_now = (Rz * Eigen::Vector3d(home_offset.x(), home_offset.y(), 0)).head<2>();
    const double h = (last.point_W - post.point_W).dot(post.axis_W);
    const Eigen::Vector3d P = LineCircle(a, w, h, post.point_W.z(), L, home_offset_now);
    // RRR: the base keeps its heading; the post turns on the vertical joint,
    // which passes through the base centre, so B = P - o either way.
    const Eigen::Vector3d B = leg.shape == "RRR" ? Eigen::Vector3d(P - o) : Eigen::Vector3d(P - Rz * o);
    const double theta = base.home_pose.z() + (leg.shape == "RRR" ? 0.0 : dtheta);
    return {B.x(), B.y(), theta};
  }
  if (leg.shape == "RRS") {
    const JointAtHome& post = leg.joints[1];
    const double L = (last.point_W - post.point_W).norm();
    const double dz = a.z() - post.point_W.z();
    const double rho = std::sqrt(L * L - dz * dz);
    const Eigen::Vector3d o = post.point_W - B_home;
    const Eigen::Vector2d home_dir = (post.point_W - last.point_W).head<2>();
    const double angle = std::atan2(home_dir.y(), home_dir.x()) + free_parameter;
    const Eigen::Vector3d P(a.x() + rho * std::cos(angle), a.y() + rho * std::sin(angle),
                            post.point_W.z());
    const Eigen::Vector3d B = P - o;
    return {B.x(), B.y(), base.home_pose.z()};
  }
  if (leg.shape == "FRRU") {
    const JointAtHome& post = leg.joints[1];
    const JointAtHome& elbow = leg.joints[2];
    const double dtheta = free_parameter;
    const Eigen::Matrix3d Rz = RotationZ(dtheta);
    const Eigen::Vector3d w = (Rz * post.axis_W).normalized();
    // Distal link: Rot(w, phi) * Rz. Its U axis c must be perpendicular to
    // the EE's U axis n: cos(phi) (c'.n) + sin(phi) ((w x c').n) = 0.
    const Eigen::Vector3d c0 = Rz * last.axis_W;
    const Eigen::Vector3d n = R_EE * last.axis2_W;
    double phi = std::atan2(-c0.dot(n), w.cross(c0).dot(n));
    phi = WrapAngle(phi);
    if (std::abs(phi) > M_PI / 2) phi = WrapAngle(phi + M_PI);  // the branch near home
    const Eigen::Matrix3d R_distal = Eigen::AngleAxisd(phi, w).toRotationMatrix() * Rz;
    const Eigen::Vector3d q = a - R_distal * (last.point_W - elbow.point_W);
    const double L = (elbow.point_W - post.point_W).norm();
    const Eigen::Vector2d home_offset = (post.point_W - elbow.point_W).head<2>();
    const Eigen::Vector2d home_offset_now = (Rz * Eigen::Vector3d(home_offset.x(), home_offset.y(), 0)).head<2>();
    const double h = (elbow.point_W - post.point_W).dot(post.axis_W.normalized());
    const Eigen::Vector3d P = LineCircle(q, w, h, post.point_W.z(), L, home_offset_now);
    const Eigen::Vector3d B = P - Rz * (post.point_W - B_home);
    return {B.x(), B.y(), base.home_pose.z() + dtheta};
  }
  throw std::runtime_error("no closed form for a leg of shape " + leg.shape);
}

}  // namespace ccma::testing

#endif  // CCMA_TESTS_LEG_CLOSED_FORM_H_
