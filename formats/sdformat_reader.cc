#include "formats/sdformat_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <tinyxml.h>
#include <sdf/Element.hh>
#include <sdf/Error.hh>
#include <sdf/Geometry.hh>
#include <sdf/Joint.hh>
#include <sdf/JointAxis.hh>
#include <sdf/Link.hh>
#include <sdf/Mesh.hh>
#include <sdf/Model.hh>
#include <sdf/Root.hh>
#include <sdf/Visual.hh>
#include <sdf/World.hh>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/internal/legged_extension.h"
#include "formats/internal/mesh_paths.h"
#include "formats/internal/robot_xml.h"
#include "formats/internal/sdf_extension_elements.h"
#include "formats/internal/sdformat_console.h"
#include "formats/internal/sdformat_world.h"
#include "formats/internal/world_includes.h"
#include "formats/internal/link_inertial.h"
#include "formats/internal/root_weld.h"
#include "formats/internal/sdformat_cost.h"
#include "formats/model_loader.h"

namespace ccma {
namespace {

// Everything a part of the reader needs to know about the file.
struct Context {
  std::string source;                                      // the file, for messages
  std::string folder;                                      // its absolute folder, for mesh uris
  Eigen::Isometry3d X_WM = Eigen::Isometry3d::Identity();  // the model frame in W
};

// libsdformat's message text (which may quote the file) for a message:
// printable ASCII, at most 200 characters (it quotes whole documents in
// some messages). Names from the file go through ccma::Quote.
std::string LibraryText(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (out.size() >= 200) return out + "...";
    const unsigned char u = static_cast<unsigned char>(c);
    out += (u == '\n' || u == '\t' || u == '\r') ? ' ' : (u < 0x20 || u > 0x7e) ? '?' : c;
  }
  return out;
}

// "FILE:LINE" of an element, "FILE" when libsdformat kept no line.
std::string Where(const Context& context, const sdf::ElementPtr& element) {
  const std::optional<int> line = element ? element->LineNumber() : std::nullopt;
  return line ? context.source + ":" + std::to_string(*line) : context.source;
}

int LineOf(const sdf::ElementPtr& element) {
  return element ? element->LineNumber().value_or(0) : 0;
}

[[noreturn]] void ThrowSdfErrors(const sdf::Errors& errors, const std::string& source) {
  std::string message = source + ": libsdformat: ";
  const std::size_t shown = std::min<std::size_t>(errors.size(), 3);
  for (std::size_t i = 0; i < shown; ++i) {
    if (i > 0) message += "; ";
    message += LibraryText(errors[i].Message());
    if (errors[i].LineNumber())
      message += " [line " + std::to_string(*errors[i].LineNumber()) + "]";
  }
  if (errors.size() > shown) message += "; and " + std::to_string(errors.size() - shown) + " more";
  throw ModelError(message);
}

Eigen::Isometry3d ToIsometry(const ignition::math::Pose3d& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() << pose.Pos().X(), pose.Pos().Y(), pose.Pos().Z();
  const Eigen::Quaterniond q(pose.Rot().W(), pose.Rot().X(), pose.Rot().Y(), pose.Rot().Z());
  if (q.norm() > 0) X.linear() = q.normalized().toRotationMatrix();
  return X;
}

// A pose in W from libsdformat's pose in the model frame; rejected when not
// finite or farther than kMaxMagnitude.
Eigen::Isometry3d PoseInWorld(const Context& context, const ignition::math::Pose3d& pose_M,
                              const std::string& where) {
  const Eigen::Isometry3d X = context.X_WM * ToIsometry(pose_M);
  if (!X.matrix().allFinite() || X.translation().cwiseAbs().maxCoeff() > kMaxMagnitude) {
    throw ModelError(where + ": pose must be finite and within 1e4 m");
  }
  return X;
}

// ------------------------------------------------------------- the XML ------

// libsdformat's memory for the file (formats/internal/sdformat_cost.h),
// refused beyond kMaxSdformatMegabytes naming the costliest element.
void CheckMemory(const internal::RobotXmlSummary& summary, const std::string& source) {
  const double megabytes = internal::SdformatMegabytes(summary);
  if (megabytes <= internal::kMaxSdformatMegabytes) return;
  std::string costliest;
  double most = -1;
  for (const auto& [name, counted] : summary.names) {
    const double cost = internal::SdformatMegabytes(name, counted.count);
    if (cost > most) most = cost, costliest = std::to_string(counted.count) + " <" + Printable(name) + "> elements";
  }
  throw ModelError(source + ": too large for libsdformat: its " + std::to_string(summary.elements) +
                   " elements (" + costliest + ") would take about " + std::to_string(static_cast<long>(megabytes)) +
                   " MB, more than the " + std::to_string(static_cast<long>(internal::kMaxSdformatMegabytes)) +
                   " MB allowed (docs/import.md)");
}

// The file as ccma accepts it before libsdformat sees it: the plain XML of
// formats/internal/robot_xml.h with an <sdf> root (libsdformat, when it
// cannot read an <sdf>, reads the text again as a URDF and follows what that
// says), no <include> (libsdformat would open the files it names: the only
// place where it opens a file of its own), within kMaxSdformatMegabytes of
// libsdformat's memory, and an `sdf version` of 1.4 or later (libsdformat
// converts an older version's file to its own, with the meaning the file has
// in its version: a 1.4 joint axis in the model frame, a 1.5 or 1.6 one
// with <use_parent_model_frame>; the reader then resolves every axis and
// pose through libsdformat's frame graph, so each keeps that meaning).
//
// A world's own <include>s (the ground plane and the sun of a Gazebo world)
// are blanked out of the text, each with a warning: they name models outside
// the file, which are not the robot. An <include> anywhere else is refused.
// Returns the text libsdformat reads.
std::string CheckXml(const std::string& text, const std::string& source, std::vector<std::string>* warnings) {
  const internal::RobotXmlSummary summary = internal::CheckRobotXml(text, source, "sdf", "an SDFormat file");
  CheckMemory(summary, source);
  TiXmlDocument document;  // safe now: TinyXML reads the same elements, at most 100 deep
  document.Parse(text.c_str(), nullptr, TIXML_ENCODING_UTF8);
  if (document.Error()) {
    throw ModelError(source + ":" + std::to_string(document.ErrorRow()) +
                     ": not valid XML: " + document.ErrorDesc());
  }
  std::string kept = text;
  if (summary.names.count("include") != 0) kept = internal::BlankWorldIncludes(document, text, source, warnings);
  internal::WarnOfComputedInertials(*document.RootElement(), source, warnings);
  const TiXmlElement* root = document.RootElement();
  const char* version = root->Attribute("version");
  int major = 0, minor = 0;
  if (version == nullptr || std::sscanf(version, "%d.%d", &major, &minor) != 2 || major < 1 ||
      (major == 1 && minor < 4)) {
    throw ModelError(source + ":" + std::to_string(root->Row()) + ": sdf version " +
                     Quote(version ? version : "") + ": SDFormat 1.4 or later is needed");
  }
  return kept;
}

// libsdformat's errors, less the one it reports for each `planar` and
// `floating` joint (SDFormat has no such types; the reader accepts them
// from `world`).
sdf::Errors Unforgiven(const sdf::Errors& errors) {
  sdf::Errors kept;
  for (const sdf::Error& e : errors) {
    const bool base = e.Code() == sdf::ErrorCode::ATTRIBUTE_INVALID &&
                      (e.Message().rfind("Joint type of planar is invalid", 0) == 0 ||
                       e.Message().rfind("Joint type of floating is invalid", 0) == 0);
    if (!base) kept.push_back(e);
  }
  return kept;
}

// ------------------------------------------------------------- meshes -------

void ReadMeshes(const sdf::Link& link, const Context& context, RobotLink* out) {
  for (uint64_t v = 0; v < link.VisualCount(); ++v) {
    const sdf::Visual* visual = link.VisualByIndex(v);
    const sdf::Geometry* geometry = visual->Geom();
    if (geometry == nullptr || geometry->MeshShape() == nullptr) continue;
    const sdf::Mesh& mesh = *geometry->MeshShape();
    const std::string where = Where(context, visual->Element()) + ": visual " +
                              Quote(visual->Name()) + " of link " + Quote(link.Name());
    ignition::math::Pose3d pose;
    const sdf::Errors errors = visual->SemanticPose().Resolve(pose, "__model__");
    if (!errors.empty()) ThrowSdfErrors(errors, where);
    RobotMesh result;
    result.file = internal::ResolveMeshPath(mesh.Uri(), context.folder);
    result.X_WM = PoseInWorld(context, pose, where);
    result.scale << mesh.Scale().X(), mesh.Scale().Y(), mesh.Scale().Z();
    if (!result.scale.allFinite() || result.scale.minCoeff() <= 0 ||
        result.scale.maxCoeff() > kMaxMagnitude) {
      throw ModelError(where + ": mesh scale must be positive, finite and at most 1e4");
    }
    out->meshes.push_back(result);
  }
}

RobotLink ReadLink(const sdf::Link& link, const Context& context) {
  RobotLink out;
  out.name = link.Name();
  out.line = LineOf(link.Element());
  const std::string where = Where(context, link.Element()) + ": link " + Quote(link.Name());
  ignition::math::Pose3d pose;
  const sdf::Errors errors = link.SemanticPose().Resolve(pose, "__model__");
  if (!errors.empty()) ThrowSdfErrors(errors, where);
  out.X_WL = PoseInWorld(context, pose, where);
  ReadMeshes(link, context, &out);
  // A link without <inertial> has SDFormat's default (libsdformat's): 1 kg,
  // inertia diag(1, 1, 1) kg m^2 at the link's origin (the reader says so:
  // DefaultInertialsWarning).
  {
    const ignition::math::Inertiald& inertial = link.Inertial();
    const ignition::math::Matrix3d& moi = inertial.MassMatrix().Moi();
    Eigen::Matrix3d I;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) I(r, c) = moi(r, c);
    }
    internal::SetLinkInertial(inertial.MassMatrix().Mass(), ToIsometry(inertial.Pose()), I, where, &out);
  }
  return out;
}

// ------------------------------------------------------------- joints -------

RobotJointType JointTypeOf(const sdf::Joint& joint, const std::string& where) {
  switch (joint.Type()) {
    case sdf::JointType::REVOLUTE:
    case sdf::JointType::CONTINUOUS:
      return RobotJointType::kRevolute;
    case sdf::JointType::PRISMATIC:
      return RobotJointType::kPrismatic;
    case sdf::JointType::FIXED:
      return RobotJointType::kFixed;
    case sdf::JointType::BALL:
      return RobotJointType::kSpherical;
    case sdf::JointType::UNIVERSAL:
      return RobotJointType::kUniversal;
    default:
      break;
  }
  const std::string type = joint.Element() ? joint.Element()->Get<std::string>("type") : "";
  if (type == "planar") return RobotJointType::kPlanar;
  if (type == "floating") return RobotJointType::kFloating;
  throw ModelError(where + ": type " + Quote(type) +
                   " is not supported (revolute, continuous, prismatic, fixed, ball, universal, "
                   "or planar or floating from world)");
}

// A floating joint from world is a legged base when it holds ccma's
// <ccma:legged .../> (formats/internal/legged_extension.h: an element of
// ccma's namespace, internal/sdf_extension_elements.h); no other joint may.
void ReadSdfLegged(const sdf::Joint& joint, const Context& context, const std::string& where, RobotJoint* out) {
  const sdf::ElementPtr element = joint.Element();
  const std::string name = std::string("<") + internal::kSdfLeggedElement + ">";
  const bool floating = out->type == RobotJointType::kFloating;
  const std::vector<sdf::ElementPtr> found = internal::CcmaSdfChildren(element, "legged");
  if (found.empty()) {
    if (!floating) return;
    throw ModelError(where + ": a floating joint from world is a legged base and needs ccma's " + name +
                     " element (body_height=\"m\", docs/import.md)" + internal::NotCcmaHint(element, "legged") +
                     "; ccma has no free-flying body");
  }
  const sdf::ElementPtr legged = found.front();
  // libsdformat keeps no line for elements of other namespaces: the joint's then.
  const std::string at = Where(context, legged->LineNumber() ? legged : element) + ": joint " + Quote(joint.Name()) +
                         ": " + name;
  if (found.size() > 1) throw ModelError(at + ": more than one");
  if (!floating) throw ModelError(at + " belongs in a floating joint from world");
  out->legged = internal::ParseLeggedAttributes(internal::CcmaSdfAttributes(legged, at), at);
}

// The unit axis `index` of a joint, in W.
Eigen::Vector3d AxisInWorld(const sdf::Joint& joint, unsigned index, const Context& context,
                            const std::string& where) {
  const sdf::JointAxis* axis = joint.Axis(index);
  const std::string name = index == 0 ? "axis" : "axis2";
  if (axis == nullptr) throw ModelError(where + ": <" + name + "> is missing");
  ignition::math::Vector3d xyz;
  const sdf::Errors errors = axis->ResolveXyz(xyz, "__model__");
  if (!errors.empty()) ThrowSdfErrors(errors, where + ": " + name);
  const Eigen::Vector3d v = context.X_WM.linear() * Eigen::Vector3d(xyz.X(), xyz.Y(), xyz.Z());
  if (!v.allFinite() || v.norm() < 1e-12)
    throw ModelError(where + ": " + name + " must be a finite, non-zero vector");
  return v.normalized();
}

// A number written in the file under `parent` (not one of libsdformat's
// defaults), or nothing.
std::optional<double> Written(const sdf::ElementPtr& parent, const std::string& name) {
  if (!parent || !parent->HasElement(name)) return std::nullopt;
  const sdf::ElementPtr element = parent->GetElement(name);
  if (!element->GetExplicitlySetInFile()) return std::nullopt;
  return element->Get<double>();
}

// <initial_position> and <limit> of a revolute or prismatic joint.
void ReadPositionAndLimits(const sdf::Joint& joint, const std::string& where, RobotJoint* out) {
  const sdf::ElementPtr axis = joint.Axis(0)->Element();
  if (const std::optional<double> q = Written(axis, "initial_position")) {
    if (!std::isfinite(*q) || std::abs(*q) > kMaxMagnitude) {
      throw ModelError(where + ": initial_position must be finite and within 1e4");
    }
    out->position = *q;
  }
  if (joint.Type() == sdf::JointType::CONTINUOUS || !axis || !axis->HasElement("limit")) return;
  const sdf::ElementPtr limit = axis->GetElement("limit");
  const std::optional<double> lower = Written(limit, "lower"), upper = Written(limit, "upper");
  // SDFormat writes "no limit" as +-1e16 (its defaults) or an infinity.
  const auto bounded = [](const std::optional<double>& v) {
    return v && std::isfinite(*v) && std::abs(*v) < 1e16;
  };
  if (!bounded(lower) || !bounded(upper)) return;
  if (std::abs(*lower) > kMaxMagnitude || std::abs(*upper) > kMaxMagnitude || *lower > *upper) {
    throw ModelError(where + ": limit lower and upper must be within 1e4, lower <= upper");
  }
  out->limited = true;
  out->lower = *lower;
  out->upper = *upper;
}

// The link a joint's parent or child frame is attached to ("world" stays).
std::string AttachedLink(const sdf::Joint& joint, bool parent, const std::string& where) {
  std::string link;
  const sdf::Errors errors = parent ? joint.ResolveParentLink(link) : joint.ResolveChildLink(link);
  if (!errors.empty()) ThrowSdfErrors(errors, where);
  return link;
}

RobotJoint ReadJoint(const sdf::Joint& joint, const Context& context) {
  RobotJoint out;
  out.name = joint.Name();
  out.line = LineOf(joint.Element());
  const std::string where =
      Where(context, joint.Element()) + ": joint " + Quote(joint.Name());
  out.type = JointTypeOf(joint, where);
  out.parent = AttachedLink(joint, true, where);
  out.child = AttachedLink(joint, false, where);
  ignition::math::Pose3d pose;
  const sdf::Errors errors = joint.SemanticPose().Resolve(pose, "__model__");
  if (!errors.empty()) ThrowSdfErrors(errors, where);
  out.X_WJ = PoseInWorld(context, pose, where);
  switch (out.type) {
    case RobotJointType::kRevolute:
    case RobotJointType::kPrismatic:
      out.axis_W = AxisInWorld(joint, 0, context, where);
      ReadPositionAndLimits(joint, where, &out);
      break;
    case RobotJointType::kUniversal:
      out.axis_W = AxisInWorld(joint, 0, context, where);
      out.axis2_W = AxisInWorld(joint, 1, context, where);
      break;
    case RobotJointType::kPlanar:
    case RobotJointType::kFloating:
      if (out.parent != kRobotWorld) {
        throw ModelError(where + ": a " + (out.type == RobotJointType::kPlanar ? "planar" : "floating") +
                         " joint must connect the ground ('world') to a mobile base");
      }
      out.axis_W = out.X_WJ.linear().col(2);
      break;
    default:
      break;
  }
  ReadSdfLegged(joint, context, where, &out);
  return out;
}

// ------------------------------------------------------------- the model ----

std::vector<double> Numbers(const std::string& text, const std::string& where, std::size_t count) {
  std::istringstream in(text);
  std::vector<double> values;
  for (double v; values.size() <= count && in >> v;) values.push_back(v);
  in.clear();
  std::string rest;
  const bool clean = !(in >> rest);
  if (!clean || values.size() != count || !std::all_of(values.begin(), values.end(), [](double v) {
        return std::isfinite(v) && std::abs(v) <= kMaxMagnitude;
      })) {
    throw ModelError(where + ": expected " + std::to_string(count) +
                     " finite numbers within 1e4, got " + Quote(text));
  }
  return values;
}

// <ccma:actuated joints="a b c"/> (written by `ccma export`): the default
// for --actuated. Names are checked by the importer.
std::vector<std::string> StoredActuated(const sdf::Model& model) {
  std::vector<std::string> names;
  const std::vector<sdf::ElementPtr> found = internal::CcmaSdfChildren(model.Element(), "actuated");
  if (found.empty()) return names;
  const sdf::ElementPtr& element = found.front();
  if (!element->HasAttribute("joints")) return names;
  std::istringstream joints(element->GetAttribute("joints")->GetAsString());
  for (std::string name; joints >> name && names.size() < 100000;) names.push_back(name);
  return names;
}

// <ccma:end_effector link=".." point="x y z" controlled="x y z yaw"/>.
void ReadEndEffector(const sdf::Model& model, const Context& context, RobotDescription* out) {
  const sdf::ElementPtr root = model.Element();
  const std::vector<sdf::ElementPtr> found = internal::CcmaSdfChildren(root, "end_effector");
  if (found.empty()) return;
  const sdf::ElementPtr& element = found.front();
  const std::string where = Where(context, root) + ": <ccma:end_effector>";
  const auto attribute = [&](const char* name) {
    return element->HasAttribute(name) ? element->GetAttribute(name)->GetAsString() : std::string();
  };
  out->end_effector.link = attribute("link");
  if (out->end_effector.link != kRobotWorld && out->FindLink(out->end_effector.link) < 0) {
    throw ModelError(where + ": link " + Quote(out->end_effector.link) +
                     " is not a link of the model");
  }
  if (element->HasAttribute("point")) {
    const std::vector<double> p = Numbers(attribute("point"), where + " point", 3);
    out->end_effector.point_L << p[0], p[1], p[2];
  }
  std::istringstream controlled(attribute("controlled"));
  const std::set<std::string> known = {"x", "y", "z", "roll", "pitch", "yaw"};
  for (std::string name; controlled >> name;) {
    const bool repeated =
        std::find(out->end_effector.controlled.begin(), out->end_effector.controlled.end(), name) !=
        out->end_effector.controlled.end();
    if (!known.count(name) || repeated) {
      throw ModelError(where + " controlled: " + Quote(name) +
                       " is not one of x y z roll pitch yaw (each once)");
    }
    out->end_effector.controlled.push_back(name);
  }
  out->has_end_effector = true;
}

// [A-Za-z0-9_-] only, at most kMaxNameLength characters, never empty.
std::string CleanName(const std::string& name) {
  std::string out;
  for (char c : name.substr(0, kMaxNameLength))
    out += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') ? c : '_';
  return out.empty() ? "robot" : out;
}

}  // namespace

RobotDescription ReadSdformatFromString(const std::string& text, const std::string& path,
                                        const std::vector<std::string>& actuated) {
  if (text.size() > kMaxSdformatFileBytes) {
    throw ModelError(path + ": larger than " + std::to_string(kMaxSdformatFileBytes) + " bytes");
  }
  internal::QuietSdformatConsole();  // before anything of libsdformat: no log file, nothing printed
  std::vector<std::string> warnings;
  const std::string kept = CheckXml(text, path, &warnings);
  sdf::Root root;
  const sdf::Errors errors = Unforgiven(root.LoadSdfString(kept));
  if (!errors.empty()) ThrowSdfErrors(errors, path);
  const sdf::Model& model = internal::TheModel(root, path, &warnings);
  Context context{path, internal::AbsoluteFolderOf(path), {}};
  ignition::math::Pose3d model_pose;
  if (!model.SemanticPose().Resolve(model_pose).empty()) model_pose = model.RawPose();
  context.X_WM = ToIsometry(model_pose);
  RobotDescription robot;
  robot.name = CleanName(model.Name());
  robot.source = path;
  robot.warnings = warnings;
  internal::ReadWorldGravity(root, path, &robot);
  for (uint64_t i = 0; i < model.LinkCount(); ++i)
    robot.links.push_back(ReadLink(*model.LinkByIndex(i), context));
  internal::AddDefaultInertialsWarning(model, path, &robot);
  internal::AddWeightlessLinksWarning(model, path, &robot);
  for (uint64_t i = 0; i < model.JointCount(); ++i)
    robot.joints.push_back(ReadJoint(*model.JointByIndex(i), context));
  internal::WeldTheRoot(model.Name(), &robot);
  robot.actuated = actuated.empty() ? StoredActuated(model) : actuated;
  ReadEndEffector(model, context, &robot);
  return robot;
}

RobotDescription ReadSdformat(const std::string& path, const std::vector<std::string>& actuated) {
  std::string text, error;
  if (!internal::ReadRegularFile(path, kMaxSdformatFileBytes, "SDFormat file", &text, &error)) {
    throw ModelError(error);
  }
  return ReadSdformatFromString(text, path, actuated);
}

}  // namespace ccma
