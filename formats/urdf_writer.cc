#include "formats/urdf_writer.h"

#include <sstream>
#include <utility>
#include <vector>

#include "formats/internal/export_geometry.h"
#include "formats/internal/legged_extension.h"

namespace ccma {
namespace {

using internal::BodyName;
using internal::HomePose;
using internal::JointWorld;
using internal::Number;
using internal::Triple;

struct UrdfLink {
  std::string name;
  Eigen::Isometry3d X_W;  // link frame in W at home
};

struct UrdfJoint {
  std::string name;
  std::string type;  // URDF type
  int parent = 0, child = 0;  // link indices
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // child frame in parent frame, q = 0
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();           // in the child frame
  std::string limit;  // the <limit> element, or ""
  std::string legged;  // a legged base's floating joint: the attributes of its <ccma_legged>, else ""
};

struct UrdfClosure {
  std::string frame_a, frame_b;
  bool six_d = true;
};

// The motion of a revolute or prismatic joint by q about / along `axis` (child frame).
Eigen::Isometry3d JointMotion(JointType type, const Eigen::Vector3d& axis, double q) {
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  if (type == JointType::kRevolute) M.linear() = Eigen::AngleAxisd(q, axis).toRotationMatrix();
  if (type == JointType::kPrismatic) M.translation() = q * axis;
  return M;
}

std::string LimitElement(const Joint& joint) {
  const std::string rest = "effort=\"0\" velocity=\"0\"/>";
  if (joint.limited) return "<limit lower=\"" + Number(joint.lower) + "\" upper=\"" + Number(joint.upper) + "\" " + rest;
  return joint.type == JointType::kPrismatic ? "<limit " + rest : "";
}

std::string UrdfType(const Joint& joint) {
  switch (joint.type) {
    case JointType::kRevolute:
      return joint.limited ? "revolute" : "continuous";
    case JointType::kPrismatic:
      return "prismatic";
    case JointType::kFixed:
      return "fixed";
    case JointType::kSpherical:
    case JointType::kUniversal:
      return "continuous";  // replaced through joint_name / joint_type
  }
  return "fixed";
}

class UrdfBuilder {
 public:
  explicit UrdfBuilder(const Model& model)
      : model_(model), names_(model), tree_(internal::BuildSpanningTree(model)) {}

  UrdfExport Build() {
    AddBodyLinks();
    AddTreeJoints();
    for (int j = 0; j < static_cast<int>(model_.joints.size()); ++j) {
      if (!tree_.in_tree[j]) AddCutJoint(j);
    }
    UrdfExport out;
    out.urdf = UrdfText();
    out.closures = ClosureText();
    out.links = static_cast<int>(links_.size());
    out.joints = static_cast<int>(joints_.size());
    out.loops = static_cast<int>(closures_.size());
    return out;
  }

 private:
  static int Link(int body) { return body + 1; }  // link 0 is world

  int AddLink(const std::string& name, const Eigen::Isometry3d& X_W) {
    links_.push_back({name, X_W});
    return static_cast<int>(links_.size()) - 1;
  }

  // A link that is a frame, not a body: listed in the closure file's
  // `frames`, so that `ccma import` fuses it into its body again.
  int AddFrame(const std::string& name, const Eigen::Isometry3d& X_W) {
    frames_.push_back(name);
    return AddLink(name, X_W);
  }

  // The link frame of a body at home (header: bases keep their body frame,
  // others sit at their parent joint's point).
  Eigen::Isometry3d BodyLinkFrame(int body) const {
    Eigen::Isometry3d X = HomePose(model_, body);
    const int j = tree_.parent_joint[body];
    if (j < 0) return X;
    const Joint& joint = model_.joints[j];
    const JointWorld jw = internal::JointInWorld(model_, joint);
    X.translation() = jw.point;
    if (joint.type == JointType::kUniversal) {
      X.linear() = tree_.reversed[body] ? internal::FrameFromAxes(jw.axis2, jw.axis)
                                        : internal::FrameFromAxes(jw.axis, jw.axis2);
    }
    return X;
  }

  // Every body's link has the body's own frame (so an end-effector point
  // given in the body's frame means the same after import); a joint frame
  // elsewhere gets a link of its own, welded to the body (JointFrameLink).
  void AddBodyLinks() {
    AddLink("world", Eigen::Isometry3d::Identity());
    for (int b = 0; b < model_.num_bodies(); ++b) AddLink(model_.bodies[b].name, HomePose(model_, b));
  }

  // The link that body's parent joint moves: the body's own when the joint
  // frame is the body frame, else `<body>_joint_frame` welded to it.
  int JointFrameLink(int body) {
    const Eigen::Isometry3d X_J = BodyLinkFrame(body);
    const Eigen::Isometry3d& X_B = links_[Link(body)].X_W;
    if ((X_J.translation() - X_B.translation()).norm() < 1e-12 && (X_J.linear() - X_B.linear()).norm() < 1e-12) {
      return Link(body);
    }
    const int link = AddFrame(names_.Claim(model_.bodies[body].name + "_joint_frame"), X_J);
    weld_after_.emplace_back(link, Link(body));
    return link;
  }

  // A model joint from link `parent` to link `child`, its `between` reversed
  // or not with respect to that direction.
  void AddModelJoint(const Joint& joint, const std::string& name, int parent, int child, bool reversed) {
    UrdfJoint u;
    u.name = name;
    u.type = UrdfType(joint);
    u.parent = parent;
    u.child = child;
    const Eigen::Isometry3d& X_WC = links_[child].X_W;
    if (joint.has_coordinate()) {
      const Eigen::Vector3d axis_W = (reversed ? -1.0 : 1.0) * internal::JointInWorld(model_, joint).axis;
      u.axis = (X_WC.linear().transpose() * axis_W).normalized();
    } else if (joint.type == JointType::kUniversal) {
      u.axis = Eigen::Vector3d::UnitX();  // the parent's axis (UJOINT_XY)
    }
    u.limit = LimitElement(joint);
    u.origin = links_[parent].X_W.inverse() * X_WC * JointMotion(joint.type, u.axis, -joint.q_home);
    if (joint.has_coordinate() && joint.q_home != 0) positions_.emplace_back(name, joint.q_home);
    if (joint.type == JointType::kSpherical || joint.type == JointType::kUniversal) {
      overrides_.emplace_back(name, joint.type == JointType::kSpherical ? "SPHERICAL" : "UJOINT_XY");
    }
    joints_.push_back(u);
  }

  void AddFixedJoint(const std::string& name, int parent, int child) {
    UrdfJoint u;
    u.name = name;
    u.type = "fixed";
    u.parent = parent;
    u.child = child;
    u.origin = links_[parent].X_W.inverse() * links_[child].X_W;
    joints_.push_back(u);
  }

  void AddTreeJoints() {
    for (int body : tree_.order) {
      const int j = tree_.parent_joint[body];
      if (j >= 0) {
        const int moved = JointFrameLink(body);
        AddModelJoint(model_.joints[j], model_.joints[j].name, Link(tree_.parent_body[body]), moved,
                      tree_.reversed[body]);
        for (const auto& [frame, child] : weld_after_) {
          AddFixedJoint(names_.Claim(links_[child].name + "_weld"), frame, child);
        }
        weld_after_.clear();
        continue;
      }
      // A mobile base hangs from world: a wheeled base by a planar joint, a
      // legged one (which also rises and tilts) by a floating joint.
      const MobileBase& base = model_.mobile_bases[model_.bodies[body].base_index];
      const bool legged = base.type == BaseType::kLegged;
      UrdfJoint u;
      u.name = names_.Claim(model_.bodies[body].name + (legged ? "_floating" : "_planar"));
      u.type = legged ? "floating" : "planar";
      if (legged) u.legged = internal::LeggedAttributes(base.legged);
      u.parent = 0;
      u.child = Link(body);
      u.origin = links_[u.child].X_W;
      joints_.push_back(u);
      planar_joints_.push_back(u.name);
    }
  }

  // A frame link fixed to `body` at X_W, named after the joint; returns its name.
  std::string AddFrameLink(const std::string& name, int body, const Eigen::Isometry3d& X_W) {
    const int link = AddFrame(name, X_W);
    AddFixedJoint(name, Link(body), link);
    return name;
  }

  void AddCutJoint(int j) {
    const Joint& joint = model_.joints[j];
    const JointWorld jw = internal::JointInWorld(model_, joint);
    Eigen::Isometry3d X_W = Eigen::Isometry3d::Identity();
    X_W.translation() = jw.point;
    if (joint.type == JointType::kUniversal) X_W.linear() = internal::FrameFromAxes(jw.axis, jw.axis2);
    const std::string name_a = names_.Claim(joint.name + "_A");
    const std::string name_b = names_.Claim(joint.name + "_B");
    if (joint.type == JointType::kFixed || joint.type == JointType::kSpherical) {
      AddFrameLink(name_a, joint.body_a, X_W);
      closures_.push_back({name_a, AddFrameLink(name_b, joint.body_b, X_W), joint.type == JointType::kFixed});
      return;
    }
    const int dummy = AddFrame(name_a, X_W);
    AddModelJoint(joint, joint.name, Link(joint.body_a), dummy, false);
    closures_.push_back({name_a, AddFrameLink(name_b, joint.body_b, X_W), true});
  }

  std::string UrdfText() const;
  std::string ClosureText() const;

  const Model& model_;
  internal::NameSet names_;
  internal::SpanningTree tree_;
  std::vector<UrdfLink> links_;
  std::vector<UrdfJoint> joints_;
  std::vector<UrdfClosure> closures_;
  std::vector<std::pair<std::string, std::string>> overrides_;  // joint_name, joint_type
  std::vector<std::pair<std::string, double>> positions_;       // joint, q_home (rad or m), when not 0
  std::vector<std::string> planar_joints_;                      // the bases' joints, base order
  std::vector<std::string> frames_;                             // links that are frames, not bodies
  std::vector<std::pair<int, int>> weld_after_;                  // (joint frame link, body link) to weld
};

std::string UrdfBuilder::UrdfText() const {
  std::ostringstream os;
  os << "<?xml version=\"1.0\"?>\n"
     << "<!-- " << model_.name << ", written by `ccma export`; loop closures, motors and the end-effector\n"
     << "     are in the closure file beside this one (.closures.yaml). -->\n"
     << "<robot name=\"" << model_.name << "\">\n";
  for (std::size_t i = 0; i < links_.size(); ++i) {
    // Links 1 .. num_bodies are the bodies (Link(b)); the others are frames the writer adds.
    const int body = static_cast<int>(i) - 1;
    const std::string inertial = body >= 0 && body < model_.num_bodies()
                                     ? internal::InertialXml(model_, body, links_[i].X_W, false, "    ")
                                     : "";
    os << "  <link name=\"" << links_[i].name << "\"" << (inertial.empty() ? "/>\n" : ">\n" + inertial + "  </link>\n");
  }
  for (const UrdfJoint& u : joints_) {
    os << "  <joint name=\"" << u.name << "\" type=\"" << u.type << "\">\n"
       << "    <parent link=\"" << links_[u.parent].name << "\"/>\n"
       << "    <child link=\"" << links_[u.child].name << "\"/>\n"
       << "    <origin xyz=\"" << Triple(u.origin.translation()) << "\" rpy=\"" << internal::RpyText(u.origin.linear())
       << "\"/>\n";
    if (u.type != "fixed" && u.type != "floating") os << "    <axis xyz=\"" << Triple(u.axis) << "\"/>\n";
    if (!u.limit.empty()) os << "    " << u.limit << "\n";
    if (!u.legged.empty()) os << "    <" << internal::kUrdfLeggedElement << u.legged << "/>\n";
    os << "  </joint>\n";
  }
  os << "</robot>\n";
  return os.str();
}

// ['a', 'b', ...]
std::string QuotedList(const std::vector<std::string>& items) {
  std::string out = "[";
  for (size_t i = 0; i < items.size(); ++i) out += (i > 0 ? ", '" : "'") + items[i] + "'";
  return out + "]";
}

std::string UrdfBuilder::ClosureText() const {
  std::ostringstream os;
  os << "# Loop closures and motors of the URDF beside this file (example-parallel-robots convention),\n"
     << "# written by `ccma export` from " << model_.name << ".\n";
  std::vector<std::string> pairs, types, motors = planar_joints_, override_names, override_types;
  for (const UrdfClosure& c : closures_) {
    pairs.push_back("['" + c.frame_a + "', '" + c.frame_b + "']");
    types.push_back(c.six_d ? "6d" : "3d");
  }
  std::string pair_text = "[";
  for (size_t i = 0; i < pairs.size(); ++i) pair_text += (i > 0 ? ", " : "") + pairs[i];
  os << "closed_loop: " << pair_text << "]\n" << "type: " << QuotedList(types) << "\n";
  for (const Joint& joint : model_.joints) {
    if (joint.actuated) motors.push_back(joint.name);
  }
  os << "name_mot: " << QuotedList(motors) << "\n";
  for (const auto& [name, type] : overrides_) {
    override_names.push_back(name);
    override_types.push_back(type);
  }
  if (!overrides_.empty()) {
    os << "joint_name: " << QuotedList(override_names) << "\n" << "joint_type: " << QuotedList(override_types) << "\n";
  }
  if (!positions_.empty()) {
    // Read the URDF's links at these positions and the loops are closed: the
    // import starts from home instead of closing the loops from q = 0.
    os << "# ccma's extension: the joint positions at home [rad or m], where the loops are closed.\n"
       << "q_home: {";
    for (size_t i = 0; i < positions_.size(); ++i) {
      os << (i > 0 ? ", '" : "'") << positions_[i].first << "': " << internal::Number(positions_[i].second);
    }
    os << "}\n";
  }
  if (!frames_.empty()) {
    os << "# ccma's extension: links that are frames, not bodies; ccma import fuses each into the body it is "
          "welded to.\n"
       << "frames: " << QuotedList(frames_) << "\n";
  }
  const EndEffector& ee = model_.end_effector;
  const Eigen::Vector3d point = links_[Link(ee.body)].X_W.inverse() * ee.p_W_home;
  os << "# ccma's extension: the end-effector link, its point in the link frame [m], the controlled components.\n"
     << "end_effector: {link: '" << BodyName(model_, ee.body) << "', point: " << internal::YamlTriple(point)
     << ", controlled: [";
  const std::vector<std::string> controlled = internal::ControlledNames(model_);
  for (size_t i = 0; i < controlled.size(); ++i) os << (i > 0 ? ", " : "") << controlled[i];
  os << "]}\n";
  return os.str();
}

}  // namespace

UrdfExport WriteUrdf(const Model& model) { return UrdfBuilder(model).Build(); }

std::string ClosureFilePath(const std::string& urdf_path) {
  const size_t slash = urdf_path.find_last_of('/');
  const size_t dot = urdf_path.find_last_of('.');
  const bool has_extension = dot != std::string::npos && (slash == std::string::npos || dot > slash + 1);
  return (has_extension ? urdf_path.substr(0, dot) : urdf_path) + ".closures.yaml";
}

}  // namespace ccma
