#include "formats/mjcf_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>
#include <tinyxml.h>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/internal/library_message.h"
#include "formats/internal/link_inertial.h"
#include "formats/internal/robot_xml.h"
#include "formats/urdf_reader.h"
#include "formats/model_loader.h"

namespace ccma {
namespace {

// mjData's stack and user data at most this much (a delta robot's needs
// about 1 MB).
constexpr double kMaxMjcfDataMegabytes = 256;

[[noreturn]] void Fail(const std::string& source, int line, const std::string& what) {
  throw ModelError(source + ":" + std::to_string(line) + ": " + what);
}

// What ccma refuses before MuJoCo reads the file (header), found with
// TinyXML (safe: robot_xml.h has bounded the nesting and the elements).
void CheckElements(const TiXmlElement& e, const std::string& source, bool in_equality) {
  for (const TiXmlElement* c = e.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
    const std::string name = c->Value();
    if (name == "include") {
      Fail(source, c->Row(), "<include> is not supported: MuJoCo would open the file it names; put its content in the file");
    }
    if (c->Attribute("file") != nullptr) {
      Fail(source, c->Row(), "<" + Printable(name) + " file=...>: ccma opens no file an MJCF names (meshes, textures, "
                             "height fields, skins); import a copy without it");
    }
    if (name == "tendon") Fail(source, c->Row(), "<tendon> is not supported: ccma has no tendons");
    if (in_equality && (name == "joint" || name == "tendon" || name == "distance")) {
      Fail(source, c->Row(), "<equality><" + name + "> is not supported: ccma closes loops with connect and weld only");
    }
    CheckElements(*c, source, name == "equality");
  }
}

// MuJoCo's warnings, kept for the description instead of printed on stdout
// (its default); its handlers are process-wide, so set once.
std::mutex warnings_mutex;
std::vector<std::string>* active_warnings = nullptr;
// MuJoCo's message (several lines, quoting the file) on one printable line.
std::string OneLineMessage(std::string text) {
  for (std::size_t at = 0; (at = text.find('\n', at)) != std::string::npos;) text.replace(at, 1, "; ");
  while (!text.empty() && (text.back() == ' ' || text.back() == ';')) text.pop_back();
  return internal::LibraryMessage(text);
}

void KeepWarning(const char* message) {
  if (active_warnings != nullptr) active_warnings->push_back("MuJoCo: " + OneLineMessage(message));
}

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

// MuJoCo's compiler on `text`, from memory: a virtual file, nothing opened.
std::unique_ptr<mjModel, ModelDeleter> Compile(const std::string& text, const std::string& source,
                                               std::vector<std::string>* warnings) {
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  const char* const kName = "ccma_import.xml";
  if (mj_makeEmptyFileVFS(&vfs, kName, static_cast<int>(text.size())) != 0) {
    throw ModelError(source + ": MuJoCo could not take the file (" + std::to_string(text.size()) + " bytes)");
  }
  std::memcpy(vfs.filedata[vfs.nfile - 1], text.data(), text.size());
  char error[1000] = "";
  std::unique_ptr<mjModel, ModelDeleter> m;
  {
    const std::lock_guard<std::mutex> lock(warnings_mutex);
    active_warnings = warnings;
    mju_user_warning = KeepWarning;
    m.reset(mj_loadXML(kName, &vfs, error, sizeof error));
    active_warnings = nullptr;
  }
  mj_deleteVFS(&vfs);
  if (!m) throw ModelError(source + ": MuJoCo: " + OneLineMessage(error));
  return m;
}

std::string Name(const mjModel* m, int type, int id, const char* fallback) {
  const char* name = mj_id2name(m, type, id);
  return name != nullptr && *name != '\0' ? std::string(name) : std::string(fallback) + std::to_string(id);
}

Eigen::Isometry3d BodyPose(const mjData* d, int body) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) X.linear()(r, c) = d->xmat[9 * body + 3 * r + c];
  }
  return X;
}

Eigen::Vector3d Vec(const mjtNum* v) { return {v[0], v[1], v[2]}; }

// The pieces of an mjModel a description is built from, at one configuration.
class MjcfConverter {
 public:
  MjcfConverter(const mjModel* m, const mjData* d, const std::string& source, RobotDescription* robot)
      : m_(m), d_(d), source_(source), robot_(robot) {}

  void Convert() {
    for (int b = 1; b < m_->nbody; ++b) AddBody(b);
    for (int e = 0; e < m_->neq; ++e) AddEquality(e);
    robot_->has_gravity = true;
    robot_->gravity = Vec(m_->opt.gravity);
    const int site = mj_name2id(m_, mjOBJ_SITE, "end_effector");
    if (site >= 0) {
      robot_->has_end_effector = true;
      robot_->end_effector.link = LinkName(m_->site_bodyid[site]);
      robot_->end_effector.point_L = Vec(m_->site_pos + 3 * site);
    }
  }

  // The actuators' joints, in actuator order (a planar base's once).
  std::vector<std::string> Actuated() const {
    std::vector<std::string> out;
    for (int a = 0; a < m_->nu; ++a) {
      if (m_->actuator_trntype[a] != mjTRN_JOINT) {
        robot_->warnings.push_back(source_ + ": actuator '" + Name(m_, mjOBJ_ACTUATOR, a, "actuator") +
                                   "' does not drive a joint: ignored");
        continue;
      }
      const std::string& joint = joint_names_[static_cast<std::size_t>(m_->actuator_trnid[2 * a])];
      if (std::find(out.begin(), out.end(), joint) == out.end()) out.push_back(joint);
    }
    return out;
  }

 private:
  std::string LinkName(int body) const { return body == 0 ? kRobotWorld : Name(m_, mjOBJ_BODY, body, "body"); }

  // Slide x, slide y, hinge z (world axes) on a body of the world.
  bool IsPlanarBase(int b) const {
    if (m_->body_parentid[b] != 0 || m_->body_jntnum[b] != 3) return false;
    const int j = m_->body_jntadr[b];
    const int types[3] = {mjJNT_SLIDE, mjJNT_SLIDE, mjJNT_HINGE};
    const Eigen::Vector3d axes[3] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
    for (int k = 0; k < 3; ++k) {
      if (m_->jnt_type[j + k] != types[k] || (Vec(d_->xaxis + 3 * (j + k)) - axes[k]).norm() > 1e-9) return false;
    }
    return true;
  }

  void AddBody(int b) {
    RobotLink link;
    link.name = LinkName(b);
    link.X_WL = BodyPose(d_, b);
    const std::string where = source_ + ": body '" + link.name + "'";
    if (m_->body_mass[b] > 0) {
      Eigen::Isometry3d X_LI = Eigen::Isometry3d::Identity();
      X_LI.translation() = Vec(m_->body_ipos + 3 * b);
      const mjtNum* q = m_->body_iquat + 4 * b;
      X_LI.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
      const Eigen::Matrix3d I = Vec(m_->body_inertia + 3 * b).asDiagonal();
      internal::SetLinkInertial(m_->body_mass[b], X_LI, I, where, &link);
    }
    robot_->links.push_back(link);
    const std::string parent = LinkName(m_->body_parentid[b]);
    const int first = m_->body_jntadr[b], count = m_->body_jntnum[b];
    joint_names_.resize(static_cast<std::size_t>(m_->njnt));
    if (IsPlanarBase(b)) {
      RobotJoint planar = Joint(link.name + "_planar", RobotJointType::kPlanar, kRobotWorld, link.name, link.X_WL);
      planar.axis_W = Eigen::Vector3d::UnitZ();
      robot_->joints.push_back(planar);
      for (int k = 0; k < 3; ++k) joint_names_[static_cast<std::size_t>(first + k)] = planar.name;
      return;
    }
    if (count == 0 || (count == 1 && m_->jnt_type[first] == mjJNT_FREE && m_->body_parentid[b] == 0)) {
      if (count == 1) {
        robot_->warnings.push_back(source_ + ": the free joint '" + Name(m_, mjOBJ_JOINT, first, "joint") +
                                   "' of root body '" + link.name + "' is welded where it is (ccma's mechanisms stand "
                                   "on the ground or on mobile bases)");
      }
      robot_->joints.push_back(Joint(link.name + (count == 1 ? "_free" : "_weld"), RobotJointType::kFixed, parent,
                                     link.name, link.X_WL));
      return;
    }
    std::string previous = parent;
    for (int k = 0; k < count; ++k) {
      const int j = first + k;
      const std::string name = Name(m_, mjOBJ_JOINT, j, "joint");
      joint_names_[static_cast<std::size_t>(j)] = name;
      // Every joint but the last moves a massless link at the body's frame.
      std::string child = link.name;
      if (k + 1 < count) {
        RobotLink between;
        between.name = link.name + "__" + name;
        between.X_WL = link.X_WL;
        robot_->links.push_back(between);
        child = between.name;
      }
      robot_->joints.push_back(TreeJoint(j, name, previous, child, link.X_WL));
      previous = child;
    }
  }

  RobotJoint Joint(const std::string& name, RobotJointType type, const std::string& parent, const std::string& child,
                   const Eigen::Isometry3d& X_WJ) const {
    RobotJoint joint;
    joint.name = name;
    joint.type = type;
    joint.parent = parent;
    joint.child = child;
    joint.X_WJ = X_WJ;
    return joint;
  }

  RobotJoint TreeJoint(int j, const std::string& name, const std::string& parent, const std::string& child,
                       const Eigen::Isometry3d& X_WB) const {
    const int type = m_->jnt_type[j];
    if (type == mjJNT_FREE) {
      throw ModelError(source_ + ": joint '" + name + "': a free joint inside the tree is not supported (ccma's bodies "
                       "are joined to the ground or to each other)");
    }
    Eigen::Isometry3d X_WJ = X_WB;
    X_WJ.translation() = Vec(d_->xanchor + 3 * j);
    RobotJoint joint = Joint(name, type == mjJNT_HINGE   ? RobotJointType::kRevolute
                                   : type == mjJNT_SLIDE ? RobotJointType::kPrismatic
                                                         : RobotJointType::kSpherical,
                             parent, child, X_WJ);
    if (type == mjJNT_HINGE || type == mjJNT_SLIDE) {
      joint.axis_W = Vec(d_->xaxis + 3 * j).normalized();
      joint.position = d_->qpos[m_->jnt_qposadr[j]];
      if (!std::isfinite(joint.position) || std::abs(joint.position) > kMaxMagnitude) {
        throw ModelError(source_ + ": joint '" + name + "': its position " + FormatG(joint.position) +
                         " (qpos, from its ref or the keyframe) is not a finite number in [-1e4, 1e4] (m or rad)");
      }
      joint.limited = m_->jnt_limited[j] != 0;
      joint.lower = m_->jnt_range[2 * j];
      joint.upper = m_->jnt_range[2 * j + 1];
    }
    return joint;
  }

  void AddEquality(int e) {
    const std::string name = Name(m_, mjOBJ_EQUALITY, e, "equality");
    const int type = m_->eq_type[e];
    if (type != mjEQ_CONNECT && type != mjEQ_WELD) {
      throw ModelError(source_ + ": equality '" + name + "': only connect and weld close loops in ccma");
    }
    if (!m_->eq_active[e]) {
      robot_->warnings.push_back(source_ + ": equality '" + name + "' is inactive: skipped");
      return;
    }
    const int body1 = m_->eq_obj1id[e], body2 = m_->eq_obj2id[e];
    const mjtNum* data = m_->eq_data + mjNEQDATA * e;
    RobotClosure closure;
    closure.name = name;
    closure.frame_a = LinkName(body1);
    closure.frame_b = LinkName(body2);
    closure.link_a = closure.frame_a;
    closure.link_b = closure.frame_b;
    const Eigen::Isometry3d X_W1 = BodyPose(d_, body1), X_W2 = BodyPose(d_, body2);
    if (type == mjEQ_CONNECT) {
      // MuJoCo 2.2's connect: the anchor in body1 (data 0-2) and in body2 (3-5).
      closure.six_d = false;
      closure.X_WA = Eigen::Isometry3d::Identity();
      closure.X_WB = Eigen::Isometry3d::Identity();
      closure.X_WA.translation() = X_W1 * Vec(data);
      closure.X_WB.translation() = X_W2 * Vec(data + 3);
    } else {
      // Its weld: body2's anchor (data 0-2, in body2) held at the relative
      // pose (data 3-5 position, 6-9 quaternion w x y z) in body1.
      Eigen::Isometry3d X_1R = Eigen::Isometry3d::Identity(), X_2A = Eigen::Isometry3d::Identity();
      X_1R.translation() = Vec(data + 3);
      X_1R.linear() = Eigen::Quaterniond(data[6], data[7], data[8], data[9]).normalized().toRotationMatrix();
      X_2A.translation() = Vec(data);
      closure.X_WA = X_W1 * X_1R;
      closure.X_WB = X_W2 * X_2A;
    }
    robot_->closures.push_back(closure);
  }

  const mjModel* m_;
  const mjData* d_;
  const std::string& source_;
  RobotDescription* robot_;
  std::vector<std::string> joint_names_;  // per MuJoCo joint: the description's joint it became
};

}  // namespace

bool HasMjcfRoot(const std::string& text) {
  std::size_t at = 0;
  while ((at = text.find('<', at)) != std::string::npos) {
    if (text.compare(at, 4, "<!--") == 0) {
      at = text.find("-->", at);
      if (at == std::string::npos) return false;
      continue;
    }
    if (text.compare(at, 2, "<?") == 0 || text.compare(at, 2, "<!") == 0) {
      ++at;
      continue;
    }
    const std::size_t end = text.find_first_of(" \t\r\n/>", at + 1);
    return end != std::string::npos && text.compare(at + 1, end - at - 1, "mujoco") == 0;
  }
  return false;
}

RobotDescription ReadMjcfFromString(const std::string& text, const std::string& path, const MjcfReadOptions& options) {
  if (text.size() > kMaxRobotFileBytes) {
    throw ModelError(path + ": larger than " + std::to_string(kMaxRobotFileBytes) + " bytes (an MJCF file)");
  }
  internal::CheckRobotXml(text, path, "mujoco", "an MJCF file");
  TiXmlDocument document;  // safe now: bounded nesting and elements
  document.Parse(text.c_str(), nullptr, TIXML_ENCODING_UTF8);
  if (document.Error() || document.RootElement() == nullptr) {
    throw ModelError(path + ":" + std::to_string(document.ErrorRow()) + ": not valid XML: " + document.ErrorDesc());
  }
  CheckElements(*document.RootElement(), path, false);
  RobotDescription robot;
  robot.source = path;
  const auto m = Compile(text, path, &robot.warnings);
  if (m->nbody - 1 > kMaxRobotLinks || m->njnt > kMaxRobotJoints || m->neq > kMaxRobotClosures) {
    throw ModelError(path + ": " + std::to_string(m->nbody - 1) + " bodies, " + std::to_string(m->njnt) + " joints and " +
                     std::to_string(m->neq) + " equalities: ccma imports at most " + std::to_string(kMaxRobotLinks) +
                     " links, " + std::to_string(kMaxRobotJoints) + " joints and " + std::to_string(kMaxRobotClosures) +
                     " closures");
  }
  if (m->ntendon > 0) throw ModelError(path + ": tendons are not supported: ccma has none");
  // mjData's memory, which the file sets (<size nstack, nuserdata>): MuJoCo
  // ends the process when it cannot allocate it, so it is bounded first.
  const double megabytes = (static_cast<double>(m->nstack) + m->nuserdata) * sizeof(mjtNum) / (1 << 20);
  if (m->nstack < 0 || m->nuserdata < 0 || megabytes > kMaxMjcfDataMegabytes) {
    throw ModelError(path + ": <size>: MuJoCo's data would take " + FormatG(megabytes, 3) + " MB, more than the " +
                     FormatG(kMaxMjcfDataMegabytes) + " MB ccma allows");
  }
  const std::unique_ptr<mjData, DataDeleter> d(mj_makeData(m.get()));
  if (!options.keyframe.empty()) {
    const int key = mj_name2id(m.get(), mjOBJ_KEY, options.keyframe.c_str());
    if (key < 0) throw ModelError(path + ": no keyframe named " + Quote(options.keyframe));
    mj_resetDataKeyframe(m.get(), d.get(), key);
  }
  mj_kinematics(m.get(), d.get());
  robot.name = m->names[0] != '\0' ? std::string(m->names) : "robot";
  for (char& c : robot.name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
  }
  if (robot.name.size() > kMaxNameLength) robot.name.resize(kMaxNameLength);
  MjcfConverter converter(m.get(), d.get(), path, &robot);
  converter.Convert();
  robot.actuated = options.actuated.empty() ? converter.Actuated() : options.actuated;
  return robot;
}

RobotDescription ReadMjcf(const std::string& path, const MjcfReadOptions& options) {
  std::string text, error;
  if (!internal::ReadRegularFile(path, kMaxRobotFileBytes, "MJCF file", &text, &error)) throw ModelError(error);
  return ReadMjcfFromString(text, path, options);
}

}  // namespace ccma
