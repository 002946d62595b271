#include "formats/urdf_reader.h"

#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/closure_file.h"
#include "formats/internal/gazebo_loop_joints.h"
#include "formats/internal/legged_extension.h"
#include "formats/internal/link_inertial.h"
#include "formats/internal/library_message.h"
#include "formats/internal/mesh_paths.h"
#include "formats/internal/robot_xml.h"
#include "formats/model_loader.h"

namespace ccma {
namespace {

// A joint's <ccma_legged> (formats/internal/legged_extension.h): its
// attributes in file order and its line.
struct UrdfLeggedElement {
  std::vector<std::pair<std::string, std::string>> attributes;
  int line = 0;
};

// The <ccma_legged> of a joint element, if any (at most one, with
// attributes only: no child element, no text).
void IndexUrdfLegged(const TiXmlElement& joint, const std::string& name, const std::string& source,
                 std::map<std::string, UrdfLeggedElement>* legged) {
  const TiXmlElement* e = joint.FirstChildElement(internal::kUrdfLeggedElement);
  if (e == nullptr) return;
  if (e->NextSiblingElement(internal::kUrdfLeggedElement) != nullptr) {
    throw ModelError(source + ":" + std::to_string(e->Row()) + ": joint " + Quote(name) + ": more than one <" +
                     internal::kUrdfLeggedElement + ">");
  }
  const std::string at = source + ":" + std::to_string(e->Row()) + ": joint " + Quote(name) + ": <" +
                         internal::kUrdfLeggedElement + ">";
  for (const TiXmlNode* inside = e->FirstChild(); inside != nullptr; inside = inside->NextSibling()) {
    const TiXmlText* text = inside->ToText();
    if (inside->ToElement() != nullptr) {
      throw ModelError(at + ": a child element " + Quote("<" + inside->ValueStr() + ">") + " (line " +
                       std::to_string(inside->Row()) + "): the element takes attributes only");
    }
    if (text != nullptr && text->ValueStr().find_first_not_of(" \t\r\n") != std::string::npos) {
      throw ModelError(at + ": text " + Quote(text->ValueStr()) + " inside: the element takes attributes only");
    }
  }
  UrdfLeggedElement& out = (*legged)[name];
  out.line = e->Row();
  for (const TiXmlAttribute* a = e->FirstAttribute(); a != nullptr; a = a->Next()) {
    out.attributes.emplace_back(a->Name(), a->Value());
  }
}

// What urdfdom does not keep: source lines, element order, and whether a
// <limit> names its range.
struct XmlIndex {
  std::vector<std::string> links, joints;  // source order
  std::map<std::string, int> line;         // "link NAME" / "joint NAME" -> line
  std::set<std::string> ranged;            // joints whose <limit> has lower or upper
  std::map<std::string, UrdfLeggedElement> legged;  // joint -> its <ccma_legged>
  std::vector<internal::GazeboJoint> gazebo_joints;  // loops closed the Gazebo way
};

XmlIndex IndexXml(const std::string& text, const std::string& source) {
  TiXmlDocument doc;
  doc.Parse(text.c_str(), nullptr, TIXML_ENCODING_UTF8);
  if (doc.Error()) {
    throw ModelError(source + ":" + std::to_string(doc.ErrorRow()) + ": not valid XML: " + doc.ErrorDesc());
  }
  const TiXmlElement* robot = doc.RootElement();
  if (robot == nullptr || robot->ValueStr() != "robot") throw ModelError(source + ": not a URDF (no <robot> element)");
  XmlIndex index;
  for (const TiXmlElement* e = robot->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    const char* name = e->Attribute("name");
    if (name == nullptr || (e->ValueStr() != "link" && e->ValueStr() != "joint")) continue;
    const bool link = e->ValueStr() == "link";
    (link ? index.links : index.joints).push_back(name);
    index.line[(link ? "link " : "joint ") + std::string(name)] = e->Row();
    const TiXmlElement* limit = e->FirstChildElement("limit");
    if (!link && limit != nullptr && (limit->Attribute("lower") != nullptr || limit->Attribute("upper") != nullptr)) {
      index.ranged.insert(name);
    }
    if (!link) IndexUrdfLegged(*e, name, source, &index.legged);
  }
  index.gazebo_joints = internal::ReadGazeboJoints(*robot, source);
  if (index.links.size() > static_cast<std::size_t>(kMaxRobotLinks) ||
      index.joints.size() + index.gazebo_joints.size() > static_cast<std::size_t>(kMaxRobotJoints)) {
    throw ModelError(source + ": " + std::to_string(index.links.size()) + " links and " +
                     std::to_string(index.joints.size()) + " joints: ccma imports at most " +
                     std::to_string(kMaxRobotLinks) + " links and " + std::to_string(kMaxRobotJoints) + " joints");
  }
  return index;
}

// Collects urdfdom's error messages (it reports through console_bridge)
// instead of letting it print them.
class CapturedErrors final : public console_bridge::OutputHandler {
 public:
  CapturedErrors() { console_bridge::useOutputHandler(this); }
  ~CapturedErrors() override { console_bridge::restorePreviousOutputHandler(); }
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && first_.empty()) first_ = text;
  }
  const std::string& first() const { return first_; }

 private:
  std::string first_;
};

urdf::ModelInterfaceSharedPtr ParseUrdf(const std::string& text, const std::string& source) {
  CapturedErrors errors;
  urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(text);
  if (!model) {
    // urdfdom's messages quote names from the file: printable, cut.
    throw ModelError(source + ": not a valid URDF: " +
                     (errors.first().empty() ? "urdfdom rejected it" : internal::LibraryMessage(errors.first())));
  }
  return model;
}

// "source:LINE: joint 'NAME'" (kind: "link" or "joint"), the name quoted.
std::string Where(const XmlIndex& index, const std::string& source, const std::string& kind, const std::string& name) {
  const auto it = index.line.find(kind + " " + name);
  return source + (it == index.line.end() ? "" : ":" + std::to_string(it->second)) + ": " + kind + " " + Quote(name);
}

// A pose, checked finite and within the documented magnitudes.
Eigen::Isometry3d Isometry(const urdf::Pose& pose, const std::string& where) {
  const Eigen::Vector3d p(pose.position.x, pose.position.y, pose.position.z);
  const Eigen::Vector4d q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  if (!p.allFinite() || !q.allFinite() || p.cwiseAbs().maxCoeff() > kMaxMagnitude || q.norm() < 1e-9) {
    throw ModelError(where + ": origin must be finite, within 1e4 m, with a valid rotation");
  }
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  X.translation() = p;
  return X;
}

RobotJointType JointType(const urdf::Joint& joint, const std::string& where) {
  switch (joint.type) {
    case urdf::Joint::REVOLUTE:
    case urdf::Joint::CONTINUOUS: return RobotJointType::kRevolute;
    case urdf::Joint::PRISMATIC: return RobotJointType::kPrismatic;
    case urdf::Joint::FIXED: return RobotJointType::kFixed;
    case urdf::Joint::PLANAR: return RobotJointType::kPlanar;
    case urdf::Joint::FLOATING:
      if (joint.parent_link_name == kRobotWorld) return RobotJointType::kFloating;
      break;
    default: break;
  }
  throw ModelError(where + ": joint type not supported (revolute, continuous, prismatic, fixed, planar or "
                           "floating from the ground; a closure file's joint_type may replace it)");
}

// A floating joint from the ground is a legged base when it holds ccma's
// <ccma_legged> (ccma has no free-flying body); no other joint may hold one.
void ReadUrdfLegged(const XmlIndex& index, const std::string& source, const std::string& where, RobotJoint* joint) {
  const auto it = index.legged.find(joint->name);
  const bool floating = joint->type == RobotJointType::kFloating;
  const std::string element = std::string("<") + internal::kUrdfLeggedElement + ">";
  if (it == index.legged.end()) {
    if (!floating) return;
    throw ModelError(where + ": a floating joint from the ground is a legged base and needs ccma's " + element +
                     " element (body_height=\"m\", docs/import.md); ccma has no free-flying body");
  }
  const std::string at = source + ":" + std::to_string(it->second.line) + ": joint " + Quote(joint->name) + ": " +
                         element;
  if (!floating) throw ModelError(at + " belongs in a floating joint from the ground ('world')");
  joint->legged = internal::ParseLeggedAttributes(it->second.attributes, at);
}

RobotJoint ReadJoint(const urdf::Joint& j, const Eigen::Isometry3d& X_WP, const XmlIndex& index,
                 const std::string& source) {
  const std::string where = Where(index, source, "joint", j.name);
  RobotJoint joint;
  joint.name = j.name;
  joint.type = JointType(j, where);
  joint.parent = j.parent_link_name;
  joint.child = j.child_link_name;
  joint.line = index.line.count("joint " + j.name) ? index.line.at("joint " + j.name) : 0;
  joint.X_WJ = X_WP * Isometry(j.parent_to_joint_origin_transform, where);
  const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
  const bool has_axis = joint.type != RobotJointType::kFixed && joint.type != RobotJointType::kFloating;
  if (has_axis && (!axis.allFinite() || axis.norm() < 1e-9 || axis.norm() > 1e9)) {
    throw ModelError(where + ": axis must be a finite, non-zero vector");
  }
  if (has_axis) joint.axis_W = joint.X_WJ.linear() * axis.normalized();
  ReadUrdfLegged(index, source, where, &joint);
  const bool ranged = index.ranged.count(j.name) > 0 && j.limits && j.type != urdf::Joint::CONTINUOUS;
  if (ranged && (joint.type == RobotJointType::kRevolute || joint.type == RobotJointType::kPrismatic)) {
    joint.limited = true;
    joint.lower = j.limits->lower;
    joint.upper = j.limits->upper;
    if (!std::isfinite(joint.lower) || !std::isfinite(joint.upper) || joint.lower > joint.upper ||
        std::abs(joint.lower) > kMaxMagnitude || std::abs(joint.upper) > kMaxMagnitude) {
      throw ModelError(where + ": limit lower and upper must be finite, within 1e4, lower <= upper");
    }
  }
  if (joint.type == RobotJointType::kPlanar && joint.parent != kRobotWorld) {
    throw ModelError(where + ": a planar joint must connect the ground ('world') to a mobile base");
  }
  return joint;
}

void AddMeshes(const urdf::Link& link, const std::string& folder, const std::string& where, RobotLink* out) {
  for (const urdf::VisualSharedPtr& visual : link.visual_array) {
    if (!visual || !visual->geometry || visual->geometry->type != urdf::Geometry::MESH) continue;
    const auto& mesh = static_cast<const urdf::Mesh&>(*visual->geometry);
    RobotMesh m;
    m.file = internal::ResolveMeshPath(mesh.filename, folder);
    m.X_WM = out->X_WL * Isometry(visual->origin, where + " visual");
    m.scale = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
    if (!m.scale.allFinite() || m.scale.minCoeff() <= 0 || m.scale.maxCoeff() > kMaxMagnitude) {
      throw ModelError(where + ": mesh scale must be positive and finite");
    }
    out->meshes.push_back(m);
  }
}

// Link poses at the zero configuration, walking the tree from the root
// without recursion (a chain may be long).
void WalkTree(const urdf::ModelInterface& urdf, const XmlIndex& index, const std::string& source,
              const std::string& folder, RobotDescription* robot) {
  std::map<std::string, Eigen::Isometry3d> X_WL;
  std::map<std::string, RobotJoint> joints;
  std::vector<std::string> pending = {urdf.getRoot()->name};
  X_WL[pending.front()] = Eigen::Isometry3d::Identity();
  while (!pending.empty()) {
    const urdf::LinkConstSharedPtr link = urdf.getLink(pending.back());
    pending.pop_back();
    for (const urdf::JointSharedPtr& j : link->child_joints) {
      RobotJoint joint = ReadJoint(*j, X_WL.at(link->name), index, source);
      X_WL[joint.child] = joint.X_WJ;
      pending.push_back(joint.child);
      joints[joint.name] = joint;
    }
  }
  const std::string root = urdf.getRoot()->name;
  if (root != kRobotWorld) {
    RobotJoint weld;
    weld.name = std::string(kRobotWorld) + "__" + root;
    weld.parent = kRobotWorld;
    weld.child = root;
    robot->joints.push_back(weld);
  }
  for (const std::string& name : index.links) {
    if (name == kRobotWorld || X_WL.count(name) == 0) continue;
    RobotLink link;
    link.name = name;
    link.X_WL = X_WL.at(name);
    link.line = index.line.at("link " + name);
    if (const urdf::InertialSharedPtr inertial = urdf.getLink(name)->inertial) {
      Eigen::Matrix3d I;
      I << inertial->ixx, inertial->ixy, inertial->ixz, inertial->ixy, inertial->iyy, inertial->iyz, inertial->ixz,
          inertial->iyz, inertial->izz;
      const std::string where = Where(index, source, "link", name);
      internal::SetLinkInertial(inertial->mass, Isometry(inertial->origin, where + ": inertial"), I, where, &link);
    }
    AddMeshes(*urdf.getLink(name), folder, Where(index, source, "link", name), &link);
    robot->links.push_back(link);
  }
  for (const std::string& name : index.joints) {
    if (joints.count(name)) robot->joints.push_back(joints.at(name));
  }
}

}  // namespace

RobotDescription ReadUrdfFromString(const std::string& text, const std::string& urdf_path) {
  if (text.size() > kMaxRobotFileBytes) {
    throw ModelError(urdf_path + ": larger than " + std::to_string(kMaxRobotFileBytes) + " bytes (a URDF file)");
  }
  internal::CheckRobotXml(text, urdf_path, "robot", "a URDF");  // before TinyXML: nesting, elements, one <robot>
  const XmlIndex index = IndexXml(text, urdf_path);
  const urdf::ModelInterfaceSharedPtr urdf = ParseUrdf(text, urdf_path);
  RobotDescription robot;
  robot.name = urdf->getName();
  robot.source = urdf_path;
  WalkTree(*urdf, index, urdf_path, internal::AbsoluteFolderOf(urdf_path), &robot);
  internal::AddGazeboJoints(index.gazebo_joints, urdf_path, &robot);
  return robot;
}

RobotDescription ReadUrdf(const std::string& urdf_path, const std::string& closures_path) {
  std::string text, error;
  if (!internal::ReadRegularFile(urdf_path, kMaxRobotFileBytes, "URDF file", &text, &error)) throw ModelError(error);
  RobotDescription robot = ReadUrdfFromString(text, urdf_path);
  if (!closures_path.empty()) ApplyClosureFile(ReadClosureFile(closures_path), &robot);
  return robot;
}

}  // namespace ccma
