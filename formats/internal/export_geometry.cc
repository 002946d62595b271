#include "formats/internal/export_geometry.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <queue>
#include <stdexcept>

#include "ccma/internal/format.h"
#include "ccma/rotation.h"

namespace ccma::internal {

Eigen::Isometry3d HomePose(const Model& model, int body) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (body == kWorld) return X;
  X.linear() = model.bodies[body].R_WB_home;
  X.translation() = model.bodies[body].p_WB_home;
  return X;
}

std::string BodyName(const Model& model, int body) { return body == kWorld ? "world" : model.bodies[body].name; }

JointWorld JointInWorld(const Model& model, const Joint& joint) {
  const Eigen::Isometry3d X_WA = HomePose(model, joint.body_a);
  const Eigen::Isometry3d X_WB = HomePose(model, joint.body_b);
  JointWorld out;
  out.point = X_WA * joint.p_A;
  out.axis = X_WA.linear() * joint.a_A;
  out.axis2 = X_WB.linear() * joint.b_B;
  return out;
}

Eigen::Matrix3d FrameFromAxes(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  Eigen::Matrix3d R;
  R.col(0) = x.normalized();
  R.col(1) = y.normalized();
  R.col(2) = R.col(0).cross(R.col(1));
  return R;
}

std::string Number(double value) { return FormatExact(value); }

std::string Triple(const Eigen::Vector3d& v) { return Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z()); }

std::string YamlTriple(const Eigen::Vector3d& v) {
  return "[" + Number(v.x()) + ", " + Number(v.y()) + ", " + Number(v.z()) + "]";
}

std::string RpyText(const Eigen::Matrix3d& R) { return Triple(RpyFromRotation(R)); }

NameSet::NameSet(const Model& model) {
  taken_.insert("world");
  for (const Body& body : model.bodies) taken_.insert(body.name);
  for (const Joint& joint : model.joints) taken_.insert(joint.name);
}

std::string NameSet::Claim(const std::string& wanted) {
  std::string name = wanted;
  for (int k = 2; taken_.count(name) > 0; ++k) name = wanted + "_" + std::to_string(k);
  taken_.insert(name);
  return name;
}

std::vector<std::string> ControlledNames(const Model& model) {
  std::vector<std::string> names;
  for (int c = 0; c < 6; ++c) {
    if (model.end_effector.controlled[c]) names.push_back(kEndEffectorComponentNames[c]);
  }
  return names;
}

namespace {

// Lower: kept in the tree first. MJCF keeps actuated joints too (an
// equality has no actuator).
int TreePriority(const Joint& joint, TreePreference preference) {
  if (preference == TreePreference::kMjcf && joint.actuated) return 1;
  switch (joint.type) {
    case JointType::kPrismatic:
    case JointType::kUniversal:
      return 1;
    case JointType::kRevolute:
      return preference == TreePreference::kMjcf ? 2 : 1;
    case JointType::kFixed:
      return 3;
    case JointType::kSpherical:
      return 4;
  }
  return 4;
}

// Union-find over nodes 0 (world) and 1 + body.
int Root(std::vector<int>& up, int n) {
  while (up[n] != n) n = up[n] = up[up[n]];
  return n;
}

struct Edge {
  int joint;  // -1 - base index for a planar joint
  int a, b;   // nodes
  int priority;
};

std::vector<Edge> GraphEdges(const Model& model, TreePreference preference) {
  std::vector<Edge> edges;
  for (int k = 0; k < model.num_bases(); ++k) edges.push_back({-1 - k, 0, 1 + model.mobile_bases[k].body, 0});
  for (int j = 0; j < static_cast<int>(model.joints.size()); ++j) {
    const Joint& joint = model.joints[j];
    edges.push_back({j, 1 + joint.body_a, 1 + joint.body_b, TreePriority(joint, preference)});
  }
  std::stable_sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.priority < y.priority; });
  return edges;
}

// Orients the kept edges away from world, breadth first.
void Orient(const Model& model, const std::vector<Edge>& kept, SpanningTree* tree) {
  const int n = model.num_bodies();
  std::vector<std::vector<const Edge*>> adjacent(n + 1);
  for (const Edge& e : kept) {
    adjacent[e.a].push_back(&e);
    adjacent[e.b].push_back(&e);
  }
  std::vector<bool> seen(n + 1, false);
  std::queue<int> todo;
  todo.push(0);
  seen[0] = true;
  while (!todo.empty()) {
    const int node = todo.front();
    todo.pop();
    for (const Edge* e : adjacent[node]) {
      const int other = e->a == node ? e->b : e->a;
      if (seen[other]) continue;
      seen[other] = true;
      const int body = other - 1;
      tree->parent_joint[body] = e->joint < 0 ? -1 : e->joint;
      tree->parent_body[body] = node - 1;
      tree->reversed[body] = e->joint >= 0 && e->a == other;
      tree->order.push_back(body);
      todo.push(other);
    }
  }
  if (static_cast<int>(tree->order.size()) != n) {
    throw std::invalid_argument("model '" + model.name + "': a body is not connected to world or a mobile base");
  }
}

}  // namespace

SpanningTree BuildSpanningTree(const Model& model, TreePreference preference) {
  const int n = model.num_bodies();
  SpanningTree tree;
  tree.parent_joint.assign(n, -1);
  tree.parent_body.assign(n, kWorld);
  tree.reversed.assign(n, false);
  tree.in_tree.assign(model.joints.size(), false);
  std::vector<int> up(n + 1);
  std::iota(up.begin(), up.end(), 0);
  std::vector<Edge> kept;
  for (const Edge& e : GraphEdges(model, preference)) {
    const int ra = Root(up, e.a), rb = Root(up, e.b);
    if (ra == rb) continue;
    up[ra] = rb;
    kept.push_back(e);
    if (e.joint >= 0) tree.in_tree[e.joint] = true;
  }
  Orient(model, kept, &tree);
  return tree;
}

std::string InertialXml(const Model& model, int body, const Eigen::Isometry3d& X_WL, bool sdformat,
                        const std::string& indent) {
  const Body& b = model.bodies[static_cast<std::size_t>(body)];
  const MassProperties& m = b.inertia;
  if (!(m.mass > 0)) return "";
  // Centre of mass and inertia in the link frame (the body frame moved to X_WL).
  const Eigen::Isometry3d X_LB = X_WL.inverse() * HomePose(model, body);
  const Eigen::Vector3d com_L = X_LB * m.com_B;
  const Eigen::Matrix3d I = X_LB.linear() * m.inertia_B * X_LB.linear().transpose();
  const std::string values[6][2] = {{"ixx", Number(I(0, 0))}, {"ixy", Number(I(0, 1))}, {"ixz", Number(I(0, 2))},
                                    {"iyy", Number(I(1, 1))}, {"iyz", Number(I(1, 2))}, {"izz", Number(I(2, 2))}};
  std::string xml = indent + "<inertial>\n";
  if (sdformat) {
    xml += indent + "  <pose>" + Triple(com_L) + " 0 0 0</pose>\n" + indent + "  <mass>" + Number(m.mass) +
           "</mass>\n" + indent + "  <inertia>";
    for (const auto& [name, value] : values) xml += "<" + name + ">" + value + "</" + name + ">";
    xml += "</inertia>\n";
  } else {
    xml += indent + "  <origin xyz=\"" + Triple(com_L) + "\" rpy=\"0 0 0\"/>\n" + indent + "  <mass value=\"" +
           Number(m.mass) + "\"/>\n" + indent + "  <inertia";
    for (const auto& [name, value] : values) xml += " " + name + "=\"" + value + "\"";
    xml += "/>\n";
  }
  return xml + indent + "</inertial>\n";
}

}  // namespace ccma::internal
