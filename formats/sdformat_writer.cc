#include "formats/sdformat_writer.h"

#include <set>
#include <sstream>
#include <vector>

#include "formats/internal/export_geometry.h"
#include "formats/internal/legged_extension.h"

namespace ccma {
namespace {

using internal::Number;
using internal::Triple;

struct SdfJoint {
  std::string name, type;  // SDFormat type
  std::string parent, child;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // W, home
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // W
  Eigen::Vector3d axis2 = Eigen::Vector3d::UnitX();
  bool has_axis = false, has_axis2 = false;
  bool limited = false;
  double lower = 0, upper = 0;
  double initial_position = 0;
  std::string legged;  // a legged base's floating joint: the attributes of its <ccma:legged>, else ""
};

std::string SdfType(const Joint& joint) {
  switch (joint.type) {
    case JointType::kRevolute:
      return joint.limited ? "revolute" : "continuous";
    case JointType::kPrismatic:
      return "prismatic";
    case JointType::kFixed:
      return "fixed";
    case JointType::kSpherical:
      return "ball";
    case JointType::kUniversal:
      return "universal";
  }
  return "fixed";
}

std::string PoseText(const Eigen::Isometry3d& X) {
  return Triple(X.translation()) + " " + internal::RpyText(X.linear());
}

class SdfBuilder {
 public:
  explicit SdfBuilder(const Model& model) : model_(model), names_(model) {
    for (const Body& body : model.bodies) body_names_.insert(body.name);
  }

  SdformatExport Build() {
    for (int b = 0; b < model_.num_bodies(); ++b) links_.push_back({model_.bodies[b].name, internal::HomePose(model_, b)});
    for (const MobileBase& base : model_.mobile_bases) AddBase(base);
    for (const Joint& joint : model_.joints) AddJoint(joint);
    SdformatExport out;
    out.sdf = Text();
    out.links = static_cast<int>(links_.size());
    out.joints = static_cast<int>(joints_.size());
    out.loops = out.joints - out.links;
    return out;
  }

 private:
  struct SdfLink {
    std::string name;
    Eigen::Isometry3d X_W;
  };

  // Links and joints share one namespace in SDFormat 1.7: a joint named like
  // a body is renamed.
  std::string JointName(const std::string& name) {
    return body_names_.count(name) > 0 ? names_.Claim(name + "_joint") : name;
  }

  // SDFormat has neither a planar nor a floating joint type; ccma (and its
  // reader) use `planar` and `floating` from world anyway (header).
  void AddBase(const MobileBase& base) {
    const Body& body = model_.bodies[base.body];
    const bool legged = base.type == BaseType::kLegged;
    SdfJoint s;
    s.name = names_.Claim(body.name + (legged ? "_floating" : "_planar"));
    s.type = legged ? "floating" : "planar";
    s.parent = "world";
    s.child = body.name;
    s.point = body.p_WB_home;
    s.has_axis = !legged;  // the plane's normal
    if (legged) s.legged = internal::LeggedAttributes(base.legged);
    joints_.push_back(s);
  }

  void AddJoint(const Joint& joint) {
    const internal::JointWorld jw = internal::JointInWorld(model_, joint);
    // world may only be a parent: swap the ends of a joint whose second body is world.
    const bool swap = joint.body_b == kWorld;
    SdfJoint s;
    s.name = JointName(joint.name);
    s.type = SdfType(joint);
    s.parent = internal::BodyName(model_, swap ? joint.body_b : joint.body_a);
    s.child = internal::BodyName(model_, swap ? joint.body_a : joint.body_b);
    s.point = jw.point;
    s.has_axis = joint.has_coordinate() || joint.type == JointType::kUniversal;
    s.has_axis2 = joint.type == JointType::kUniversal;
    s.axis = joint.type == JointType::kUniversal ? (swap ? jw.axis2 : jw.axis) : (swap ? -1.0 : 1.0) * jw.axis;
    s.axis2 = swap ? jw.axis : jw.axis2;
    s.limited = joint.limited;
    s.lower = joint.lower;
    s.upper = joint.upper;
    s.initial_position = joint.q_home;
    joints_.push_back(s);
    if (joint.actuated) actuated_joints_.push_back(s.name);
  }

  const SdfLink& FindLink(const std::string& name) const {
    for (const SdfLink& link : links_) {
      if (link.name == name) return link;
    }
    return links_.front();  // not reached: every child is a link
  }

  void WriteJoint(std::ostream& os, const SdfJoint& s) const;
  std::string Text() const;

  const Model& model_;
  internal::NameSet names_;
  std::set<std::string> body_names_;
  std::vector<SdfLink> links_;
  std::vector<SdfJoint> joints_;
  std::vector<std::string> actuated_joints_;  // the actuated model joints, file order
};

void SdfBuilder::WriteJoint(std::ostream& os, const SdfJoint& s) const {
  // The joint frame: at the joint point, world orientation, relative to the child.
  Eigen::Isometry3d X_WJ = Eigen::Isometry3d::Identity();
  X_WJ.translation() = s.point;
  os << "    <joint name=\"" << s.name << "\" type=\"" << s.type << "\">\n"
     << "      <parent>" << s.parent << "</parent>\n"
     << "      <child>" << s.child << "</child>\n"
     << "      <pose>" << PoseText(FindLink(s.child).X_W.inverse() * X_WJ) << "</pose>\n";
  if (s.has_axis) {
    os << "      <axis>\n        <xyz>" << Triple(s.axis.normalized()) << "</xyz>\n";
    if (s.limited) {
      os << "        <limit>\n          <lower>" << Number(s.lower) << "</lower>\n          <upper>" << Number(s.upper)
         << "</upper>\n        </limit>\n";
    }
    if (s.initial_position != 0.0) {
      os << "        <initial_position>" << Number(s.initial_position) << "</initial_position>\n";
    }
    os << "      </axis>\n";
  }
  if (s.has_axis2) os << "      <axis2>\n        <xyz>" << Triple(s.axis2.normalized()) << "</xyz>\n      </axis2>\n";
  if (!s.legged.empty()) os << "      <" << internal::kSdfLeggedElement << s.legged << "/>\n";
  os << "    </joint>\n";
}

std::string SdfBuilder::Text() const {
  std::ostringstream os;
  os << "<?xml version=\"1.0\"?>\n"
     << "<!-- " << model_.name << ", written by `ccma export`: links posed at home; ccma:actuated lists the\n"
     << "     actuated joints (their controls follow the bases'); ccma:end_effector the end-effector. -->\n"
     << "<sdf version=\"1.7\" xmlns:ccma=\"" << internal::kCcmaSdfNamespace << "\">\n"
     << "  <model name=\"" << model_.name << "\">\n";
  for (std::size_t i = 0; i < links_.size(); ++i) {  // links 0 .. num_bodies - 1 are the bodies
    const std::string inertial = static_cast<int>(i) < model_.num_bodies()
                                     ? internal::InertialXml(model_, static_cast<int>(i), links_[i].X_W, true, "      ")
                                     : "";
    os << "    <link name=\"" << links_[i].name << "\">\n      <pose>" << PoseText(links_[i].X_W) << "</pose>\n"
       << inertial << "    </link>\n";
  }
  for (const SdfJoint& s : joints_) WriteJoint(os, s);
  std::string actuated;
  for (const std::string& name : actuated_joints_) actuated += (actuated.empty() ? "" : " ") + name;
  const EndEffector& ee = model_.end_effector;
  std::string controlled;
  for (const std::string& c : internal::ControlledNames(model_)) controlled += (controlled.empty() ? "" : " ") + c;
  if (!actuated.empty()) os << "    <ccma:actuated joints=\"" << actuated << "\"/>\n";
  os << "    <ccma:end_effector link=\"" << internal::BodyName(model_, ee.body) << "\" point=\""
     << Triple(ee.p_B) << "\" controlled=\"" << controlled << "\"/>\n"
     << "  </model>\n</sdf>\n";
  return os.str();
}

}  // namespace

SdformatExport WriteSdformat(const Model& model) { return SdfBuilder(model).Build(); }

}  // namespace ccma
