#include "formats/model_generator.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ccma {
namespace {

std::string Vec12(const Eigen::Vector3d& v) {
  std::ostringstream os;
  os << std::setprecision(12) << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return os.str();
}

}  // namespace

std::string GenerateStewartModel(const StewartOptions& o) {
  if (o.agents < 3) throw std::invalid_argument("a Stewart-like model needs at least 3 agents");
  std::ostringstream bodies, bases, joints;
  const double z_base_joint = 0.1;
  for (int k = 0; k < o.agents; ++k) {
    const double angle = 2.0 * M_PI * k / o.agents;
    // Alternate the attachment to either side, as a Stewart platform does.
    const double attach = angle + (k % 2 == 0 ? 1 : -1) * o.attachment_offset;
    const Eigen::Vector3d base(o.base_radius * std::cos(angle), o.base_radius * std::sin(angle), 0.0);
    const Eigen::Vector3d post_joint = base + Eigen::Vector3d(0, 0, z_base_joint);
    const Eigen::Vector3d post_top = base + Eigen::Vector3d(0, 0, o.post_height);
    const Eigen::Vector3d sphere(o.platform_radius * std::cos(attach),
                                 o.platform_radius * std::sin(attach), o.platform_height);
    // The link swings in the vertical plane through the post and the sphere.
    const Eigen::Vector3d reach = sphere - post_top;
    const Eigen::Vector3d axis = Eigen::Vector3d(reach.y(), -reach.x(), 0).normalized();
    const std::string n = std::to_string(k);
    bodies << "  - {name: post" << n << ", position: " << Vec12(post_joint) << "}\n"
           << "  - {name: link" << n << ", position: " << Vec12((post_top + sphere) / 2) << "}\n";
    // From 6 agents on, each reduced R-R-S leg constrains one distance; below
    // that, complete bases with welded posts (F-R-S, as 6dof_symmetric)
    // constrain two each, so every generated model is rigid.
    const bool reduced = o.agents >= 6;
    bases << "  - {name: base" << n << ", type: omni, actuation: "
          << (reduced ? "reduced" : "complete") << ", pose: "
          << Vec12(Eigen::Vector3d(base.x(), base.y(), angle)) << "}\n";
    joints << "  - {type: " << (reduced ? "revolute" : "fixed") << ", between: [base" << n << ", post"
           << n << "], point: " << Vec12(post_joint) << (reduced ? ", axis: [0, 0, 1]}\n" : "}\n")
           << "  - {type: revolute, between: [post" << n << ", link" << n << "], point: "
           << Vec12(post_top) << ", axis: " << Vec12(axis) << "}\n"
           << "  - {type: spherical, between: [link" << n << ", ee], point: " << Vec12(sphere) << "}\n";
  }
  std::ostringstream model;
  model << "name: stewart_" << o.agents << "_agents\n"
        << "description: \"Generated: " << o.agents
        << (o.agents >= 6 ? " reduced omni bases, R-R-S legs" : " complete omni bases, F-R-S legs")
        << ", Stewart-like layout (family of 6dof_six_agents).\"\n"
        << "bodies:\n  - {name: ee, position: " << Vec12(Eigen::Vector3d(0, 0, o.platform_height)) << "}\n"
        << bodies.str() << "mobile_bases:\n" << bases.str() << "joints:\n" << joints.str()
        << "end_effector:\n  body: ee\n  point: " << Vec12(Eigen::Vector3d(0, 0, o.platform_height))
        << "\n  controlled: [x, y, z, roll, pitch, yaw]\n";
  return model.str();
}

std::string GenerateStewartGoughModel(const StewartOptions& o) {
  if (o.agents < 6) throw std::invalid_argument("a Stewart-Gough platform needs at least 6 legs");
  std::ostringstream bodies, joints;
  for (int k = 0; k < o.agents; ++k) {
    const double angle = 2.0 * M_PI * k / o.agents;
    const double attach = angle + (k % 2 == 0 ? 1 : -1) * o.attachment_offset;
    const Eigen::Vector3d ground(o.base_radius * std::cos(angle), o.base_radius * std::sin(angle), 0.0);
    const Eigen::Vector3d top(o.platform_radius * std::cos(attach), o.platform_radius * std::sin(attach),
                              o.platform_height);
    const Eigen::Vector3d leg = top - ground;
    // Universal axes: both perpendicular to the leg, so it cannot spin.
    const Eigen::Vector3d a1 = Eigen::Vector3d(leg.y(), -leg.x(), 0).normalized();
    const Eigen::Vector3d a2 = leg.cross(a1).normalized();
    const std::string n = std::to_string(k);
    bodies << "  - {name: lower" << n << ", position: " << Vec12(ground + 0.25 * leg) << "}\n"
           << "  - {name: upper" << n << ", position: " << Vec12(ground + 0.75 * leg) << "}\n";
    joints << "  - {type: universal, between: [world, lower" << n << "], point: " << Vec12(ground)
           << ", axes: [" << Vec12(a1) << ", " << Vec12(a2) << "]}\n"
           << "  - {name: leg" << n << ", type: prismatic, actuated: true, limits: [-0.1, 0.1], between: [lower" << n
           << ", upper" << n << "], point: " << Vec12(ground + 0.5 * leg) << ", axis: " << Vec12(leg) << "}\n"
           << "  - {type: spherical, between: [upper" << n << ", ee], point: " << Vec12(top) << "}\n";
  }
  std::ostringstream model;
  model << "name: stewart_gough_" << o.agents << "_legs\n"
        << "description: \"Generated: " << o.agents
        << "-UPS Stewart-Gough platform: universal at the ground, actuated prismatic (leg<i>, "
           "+-0.1 m), spherical at the platform; no mobile base.\"\n"
        << "bodies:\n  - {name: ee, position: " << Vec12(Eigen::Vector3d(0, 0, o.platform_height)) << "}\n"
        << bodies.str() << "joints:\n" << joints.str()
        << "end_effector:\n  body: ee\n  point: " << Vec12(Eigen::Vector3d(0, 0, o.platform_height))
        << "\n  controlled: [x, y, z, roll, pitch, yaw]\n";
  return model.str();
}

// The family of models/6dof_three_legged.yaml with any number of quadrupeds.
std::string GenerateLeggedModel(const LeggedOptions& o) {
  if (o.agents < 3) throw std::invalid_argument("a platform on legged agents needs at least 3 of them");
  std::ostringstream bodies, bases, joints;
  const double hinge_z = o.body_height + o.post_height;
  for (int k = 0; k < o.agents; ++k) {
    // The first quadruped on +y, the others evenly round, each facing the centre.
    const double angle = M_PI / 2 + 2.0 * M_PI * k / o.agents;
    const Eigen::Vector3d radial(std::cos(angle), std::sin(angle), 0.0);
    const Eigen::Vector3d hinge = o.base_radius * radial + Eigen::Vector3d(0, 0, hinge_z);
    const Eigen::Vector3d ball = o.platform_radius * radial + Eigen::Vector3d(0, 0, o.platform_height);
    const Eigen::Vector3d tangent(-radial.y(), radial.x(), 0.0);
    const std::string n = std::to_string(k);
    bodies << "  - {name: arm" << n << ", position: " << Vec12((hinge + ball) / 2) << "}\n";
    bases << "  - name: dog" << n << "\n    type: legged\n    pose: [" << std::setprecision(12)
          << o.base_radius * radial.x() << ", " << o.base_radius * radial.y() << ", "
          << std::atan2(-radial.y(), -radial.x()) << "]\n    body_height: " << o.body_height
          << "\n    body_limits: {height: [" << o.body_height - 0.15 << ", " << o.body_height + 0.1
          << "], roll: [-0.25, 0.25], pitch: [-0.25, 0.25]}\n    footprint: [0.7, 0.3]\n";
    joints << "  - {name: hinge" << n << ", type: revolute, between: [dog" << n << ", arm" << n
           << "], point: " << Vec12(hinge) << ", axis: " << Vec12(tangent) << "}\n"
           << "  - {name: ball" << n << ", type: spherical, between: [arm" << n << ", ee], point: "
           << Vec12(ball) << "}\n";
  }
  const Eigen::Vector3d ee(0, 0, o.platform_height);
  std::ostringstream model;
  model << "name: legged_" << o.agents << "_agents\n"
        << "description: \"Generated: a 6-DOF platform on " << o.agents
        << " legged agents, each body carrying an arm on a hinge that holds the platform in a ball joint "
           "(the family of 6dof_three_legged).\"\n"
        << "bodies:\n  - {name: ee, position: " << Vec12(ee) << "}\n"
        << bodies.str() << "mobile_bases:\n" << bases.str() << "joints:\n" << joints.str()
        << "end_effector:\n  body: ee\n  point: " << Vec12(ee) << "\n  controlled: [x, y, z, roll, pitch, yaw]\n";
  return model.str();
}

}  // namespace ccma
