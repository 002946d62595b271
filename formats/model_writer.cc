#include "formats/model_writer.h"

#include <cstdio>
#include <sstream>
#include <string>
#include <utility>

#include "ccma/base_kind.h"
#include "ccma/internal/format.h"
#include "ccma/rotation.h"

namespace ccma {
namespace {

std::string Num(double value) { return FormatExact(value); }

std::string Vec(const Eigen::Vector3d& v) { return "[" + Num(v.x()) + ", " + Num(v.y()) + ", " + Num(v.z()) + "]"; }

const Body& Frame(const Model& model, int body) {
  static const Body kGround;
  return body == kWorld ? kGround : model.bodies[body];
}

// `text` as a YAML double-quoted scalar (control characters escaped).
std::string Quoted(const std::string& text) {
  std::string out = "\"";
  for (const unsigned char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\x%02x", c);
      out += escaped;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

// A name ([A-Za-z0-9_-], from the model or a robot file) as a YAML scalar
// that reads back as that string: quoted where plain YAML would read it as
// null (`null`, `Null`, `NULL`) or as a list entry (`-`).
std::string YamlName(const std::string& name) {
  const bool special = name == "null" || name == "Null" || name == "NULL" || name.empty() || name[0] == '-';
  return special ? "'" + name + "'" : name;
}

std::string YamlBodyName(const Model& model, int body) {
  return body == kWorld ? "world" : YamlName(model.bodies[body].name);
}

void WriteMeshes(const Body& body, std::ostringstream& out) {
  if (body.meshes.empty()) return;
  out << "    meshes:\n";
  for (const BodyMesh& mesh : body.meshes) {
    const Eigen::Matrix3d R_WM = body.R_WB_home * mesh.R_BM;
    out << "      - {file: " << Quoted(mesh.file) << ", position: " << Vec(body.R_WB_home * mesh.p_BM + body.p_WB_home)
        << ", rpy: " << Vec(RpyFromRotation(R_WM)) << ", scale: " << Vec(mesh.scale) << "}\n";
  }
}

// mass, com and inertia (world coordinates and axes at home), those given.
void WriteMass(const Body& body, const std::string& indent, std::ostringstream& out) {
  const MassProperties& m = body.inertia;
  if (m.mass > 0) {
    out << indent << "mass: " << Num(m.mass) << "\n"
        << indent << "com: " << Vec(body.R_WB_home * m.com_B + body.p_WB_home) << "\n";
  }
  if (!m.inertia_B.isZero(0)) {
    const Eigen::Matrix3d I = body.R_WB_home * m.inertia_B * body.R_WB_home.transpose();
    out << indent << "inertia: [" << Num(I(0, 0)) << ", " << Num(I(1, 1)) << ", " << Num(I(2, 2)) << ", "
        << Num(I(0, 1)) << ", " << Num(I(0, 2)) << ", " << Num(I(1, 2)) << "]\n";
  }
}

void WriteBodies(const Model& model, std::ostringstream& out) {
  bool any = false;
  for (const Body& body : model.bodies) any = any || !body.is_mobile_base();
  out << (any ? "bodies:\n" : "bodies: []\n");
  for (const Body& body : model.bodies) {
    if (body.is_mobile_base()) continue;
    out << "  - name: " << YamlName(body.name) << "\n    position: " << Vec(body.p_WB_home) << "\n    rpy: "
        << Vec(RpyFromRotation(body.R_WB_home)) << "\n";
    WriteMass(body, "    ", out);
    WriteMeshes(body, out);
  }
}

// A legged base's body_height, body_limits (those given) and footprint.
void WriteLeggedBody(const LeggedBody& body, std::ostringstream& out) {
  out << "    body_height: " << Num(body.height) << "\n";
  std::string limits;
  const std::pair<const char*, const ControlRange*> ranges[] = {
      {"height", &body.height_limits}, {"roll", &body.roll_limits}, {"pitch", &body.pitch_limits}};
  for (const auto& [name, range] : ranges) {
    if (!range->limited) continue;
    limits += std::string(limits.empty() ? "" : ", ") + name + ": [" + Num(range->lower) + ", " + Num(range->upper) + "]";
  }
  if (!limits.empty()) out << "    body_limits: {" << limits << "}\n";
  if (body.footprint.minCoeff() > 0) {
    out << "    footprint: [" << Num(body.footprint.x()) << ", " << Num(body.footprint.y()) << "]\n";
  }
}

void WriteBases(const Model& model, std::ostringstream& out) {
  if (model.mobile_bases.empty()) return;
  out << "mobile_bases:\n";
  const CollisionGeometry& collision = model.collision;
  for (std::size_t k = 0; k < model.mobile_bases.size(); ++k) {
    const MobileBase& base = model.mobile_bases[k];
    const bool differential = base.type == BaseType::kDifferential;
    const bool legged = base.type == BaseType::kLegged;
    out << "  - name: " << YamlName(base.name) << "\n    type: " << KindOf(base).name() << "\n";
    // A legged base has no `actuation` (all six controls are effective).
    if (!legged) out << "    actuation: " << (base.actuation == Actuation::kReduced ? "reduced" : "complete") << "\n";
    out << "    pose: " << Vec(base.home_pose) << "\n";
    if (legged) WriteLeggedBody(base.legged, out);
    if (differential) {
      out << "    wheels: {track: " << Num(base.differential.track) << ", radius: " << Num(base.differential.radius)
          << "}\n";
    }
    if (collision.enabled && k < collision.base_radii.size() && collision.base_radii[k] != collision.base_radius) {
      out << "    radius: " << Num(collision.base_radii[k]) << "\n";
    }
    WriteMass(model.bodies[base.body], "    ", out);
    WriteMeshes(model.bodies[base.body], out);
  }
}

void WriteJoint(const Model& model, const Joint& joint, std::ostringstream& out) {
  const Body& A = Frame(model, joint.body_a);
  const Body& B = Frame(model, joint.body_b);
  out << "  - name: " << YamlName(joint.name) << "\n    type: " << JointTypeName(joint.type) << "\n    between: ["
      << YamlBodyName(model, joint.body_a) << ", " << YamlBodyName(model, joint.body_b) << "]\n    point: "
      << Vec(A.R_WB_home * joint.p_A + A.p_WB_home) << "\n";
  if (joint.has_coordinate()) out << "    axis: " << Vec(A.R_WB_home * joint.a_A) << "\n";
  if (joint.type == JointType::kUniversal) {
    out << "    axes: [" << Vec(A.R_WB_home * joint.a_A) << ", " << Vec(B.R_WB_home * joint.b_B) << "]\n";
  }
  // Always written (also 0): the file says what every coordinate reads at home.
  if (joint.has_coordinate()) out << "    q_home: " << Num(joint.q_home) << "\n";
  if (joint.actuated) out << "    actuated: true\n";
  if (joint.limited) out << "    limits: [" << Num(joint.lower) << ", " << Num(joint.upper) << "]\n";
}

void WriteEndEffector(const Model& model, std::ostringstream& out) {
  const EndEffector& ee = model.end_effector;
  out << "end_effector:\n  body: " << YamlName(model.bodies[ee.body].name) << "\n  point: " << Vec(ee.p_W_home)
      << "\n  controlled: [";
  const char* separator = "";
  for (int c = 0; c < 6; ++c) {
    if (!ee.controlled[c]) continue;
    out << separator << kEndEffectorComponentNames[c];
    separator = ", ";
  }
  out << "]\n";
}

void WriteObstacles(const Model& model, std::ostringstream& out) {
  if (model.collision.obstacles.empty()) return;
  out << "obstacles:\n";
  for (const Obstacle& o : model.collision.obstacles) {
    out << "  - {name: " << o.name << ", ";
    if (o.shape == ObstacleShape::kCylinder) {
      out << "cylinder: {center: [" << Num(o.center.x()) << ", " << Num(o.center.y()) << "], radius: " << Num(o.radius)
          << ", height: " << Num(o.z_max) << "}}\n";
    } else {
      out << "box: {center: " << Vec(o.center) << ", size: " << Vec(o.size) << ", yaw: " << Num(o.yaw) << "}}\n";
    }
  }
}

// `collision:` (capsule ends in world coordinates at home) and `obstacles:`,
// when the model has collision geometry.
void WriteCollision(const Model& model, std::ostringstream& out) {
  const CollisionGeometry& c = model.collision;
  if (!c.enabled) return;
  out << "collision:\n  margin: " << Num(c.margin) << "\n  base_radius: " << Num(c.base_radius)
      << "\n  base_height: " << Num(c.base_height) << "\n";
  if (!c.links.empty()) out << "  links:\n";
  for (const CollisionCapsule& capsule : c.links) {
    const Body& body = model.bodies[capsule.body];
    out << "    - {body: " << body.name << ", from: " << Vec(body.R_WB_home * capsule.a_B + body.p_WB_home)
        << ", to: " << Vec(body.R_WB_home * capsule.b_B + body.p_WB_home) << ", radius: " << Num(capsule.radius)
        << "}\n";
  }
  if (!c.ignore.empty()) out << "  ignore:\n";
  for (const auto& pair : c.ignore) out << "    - [" << pair.first << ", " << pair.second << "]\n";
  WriteObstacles(model, out);
}

}  // namespace

std::string WriteModelYaml(const Model& model, const std::string& header) {
  std::ostringstream out;
  std::istringstream lines(header);
  for (std::string line; std::getline(lines, line);) out << "# " << line << "\n";
  out << "name: " << YamlName(model.name) << "\n";
  if (!model.description.empty()) out << "description: " << Quoted(model.description) << "\n";
  if (model.gravity != Model().gravity) out << "gravity: " << Vec(model.gravity) << "\n";
  WriteBodies(model, out);
  WriteBases(model, out);
  out << "joints:\n";
  for (const Joint& joint : model.joints) WriteJoint(model, joint, out);
  WriteEndEffector(model, out);
  WriteCollision(model, out);
  return out.str();
}

}  // namespace ccma
