#include "formats/mjcf_writer.h"

#include <map>
#include <sstream>
#include <utility>
#include <stdexcept>
#include <vector>

#include "ccma/base_kind.h"
#include "formats/internal/export_geometry.h"

namespace ccma {
namespace {

using internal::Number;
using internal::Triple;

// MuJoCo's quaternion order: w x y z.
std::string QuatText(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return Number(q.w()) + " " + Number(q.x()) + " " + Number(q.y()) + " " + Number(q.z());
}

struct MjcfJoint {
  std::string name, type;  // hinge, slide, ball
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();   // in the body frame (at qpos0)
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // in the body frame (at qpos0)
  double ref = 0;
  bool limited = false;
  double lower = 0, upper = 0;
};

struct MjcfEquality {
  std::string text;  // the element
};

class MjcfBuilder {
 public:
  explicit MjcfBuilder(const Model& model)
      : model_(model), names_(model), tree_(internal::BuildSpanningTree(model, internal::TreePreference::kMjcf)),
        joints_of_(model.num_bodies()), children_(model.num_bodies() + 1) {}

  MjcfExport Build() {
    for (const int body : tree_.order) children_[tree_.parent_body[body] + 1].push_back(body);
    for (int k = 0; k < model_.num_bases(); ++k) AddBase(k);
    for (const int body : tree_.order) {
      if (tree_.parent_joint[body] >= 0) AddTreeJoint(body);
    }
    for (int j = 0; j < static_cast<int>(model_.joints.size()); ++j) {
      if (!tree_.in_tree[j]) AddCut(j);
    }
    AddActuators();
    MjcfExport out;
    out.mjcf = Text();
    out.bodies = model_.num_bodies() + (model_.end_effector.payload.mass > 0 ? 1 : 0);
    for (const std::vector<MjcfJoint>& joints : joints_of_) out.joints += static_cast<int>(joints.size());
    out.equalities = static_cast<int>(equalities_.size());
    out.actuators = static_cast<int>(actuators_.size());
    for (int j = 0; j < static_cast<int>(model_.joints.size()); ++j) out.loops += tree_.in_tree[j] ? 0 : 1;
    return out;
  }

 private:
  Eigen::Isometry3d Home(int body) const { return internal::HomePose(model_, body); }

  // A base's controls as joints of its body: slides and hinges along and
  // about world axes (expressed in the body frame at home), each `ref` its
  // home control, so that qpos is the control (header).
  void AddBase(int k) {
    const MobileBase& base = model_.mobile_bases[static_cast<std::size_t>(k)];
    const BaseKind& kind = KindOf(base);
    const Eigen::VectorXd home = kind.HomeControls(base);
    const Eigen::Matrix3d R0 = model_.bodies[base.body].R_WB_home;
    const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
    std::vector<MjcfJoint>& joints = joints_of_[static_cast<std::size_t>(base.body)];
    std::vector<std::string> names(static_cast<std::size_t>(kind.num_controls()));
    const auto add = [&](int i, const char* type, const Eigen::Vector3d& axis) {
      MjcfJoint j;
      j.name = names_.Claim(base.name + "_" + kind.controls()[static_cast<std::size_t>(i)].name);
      j.type = type;
      j.axis = axis;
      j.ref = home[i];
      joints.push_back(j);
      names[static_cast<std::size_t>(i)] = j.name;
    };
    add(0, "slide", R0.transpose() * X);
    add(1, "slide", R0.transpose() * Y);
    add(2, "hinge", R0.transpose() * Z);
    if (kind.num_controls() == 6) {
      // Legged (x, y, heading, height, roll, pitch; R = Rz(heading)
      // Ry(pitch) Rx(roll)): height along world z, then pitch about the
      // heading's y (in the body frame at home, turned back by the home roll),
      // then roll about the body's x.
      const double roll0 = home[4];
      add(3, "slide", R0.transpose() * Z);
      add(5, "hinge", Eigen::AngleAxisd(roll0, X).toRotationMatrix().transpose() * Y);
      add(4, "hinge", X);
    }
    control_joints_.insert(control_joints_.end(), names.begin(), names.end());
  }

  // The joint that joins `body` to its parent, in the body's frame.
  void AddTreeJoint(int body) {
    const Joint& joint = model_.joints[static_cast<std::size_t>(tree_.parent_joint[body])];
    const internal::JointWorld jw = internal::JointInWorld(model_, joint);
    const Eigen::Isometry3d X_WC = Home(body);
    const bool reversed = tree_.reversed[body];
    std::vector<MjcfJoint>& joints = joints_of_[static_cast<std::size_t>(body)];
    MjcfJoint j;
    j.name = joint.name;
    j.pos = X_WC.inverse() * jw.point;
    switch (joint.type) {
      case JointType::kRevolute:
      case JointType::kPrismatic:
        // q turns (moves) B relative to A about (along) a: the child is B,
        // or A turning about -a.
        j.type = joint.type == JointType::kRevolute ? "hinge" : "slide";
        j.axis = X_WC.linear().transpose() * ((reversed ? -1.0 : 1.0) * jw.axis);
        j.ref = joint.q_home;
        j.limited = joint.limited;
        j.lower = joint.lower;
        j.upper = joint.upper;
        joints.push_back(j);
        break;
      case JointType::kSpherical:
        j.type = "ball";
        joints.push_back(j);
        break;
      case JointType::kUniversal: {
        // The axis fixed in the parent first, then the child's.
        j.type = "hinge";
        j.axis = X_WC.linear().transpose() * (reversed ? jw.axis2 : jw.axis);
        joints.push_back(j);
        MjcfJoint second = j;
        second.name = names_.Claim(joint.name + "_2");
        second.axis = X_WC.linear().transpose() * (reversed ? jw.axis : jw.axis2);
        joints.push_back(second);
        break;
      }
      case JointType::kFixed:
        break;  // welded: no joint
    }
    if (joint.actuated) actuated_tree_joints_[tree_.parent_joint[body]] = j.name;
  }

  // `body1` and its anchor [m] in body1's frame; world cannot be body1 of a
  // connect that MuJoCo anchors there, so the ends swap when A is world.
  std::string Connect(const std::string& name, int body_a, int body_b, const Eigen::Vector3d& point_W) const {
    const int first = body_a == kWorld ? body_b : body_a, second = body_a == kWorld ? body_a : body_b;
    return "<connect name=\"" + name + "\" body1=\"" + internal::BodyName(model_, first) + "\" body2=\"" +
           internal::BodyName(model_, second) + "\" anchor=\"" + Triple(Home(first).inverse() * point_W) +
           "\" solref=\"" + kMjcfSolref + "\" solimp=\"" + kMjcfSolimp + "\"/>";
  }

  void AddCut(int j) {
    const Joint& joint = model_.joints[static_cast<std::size_t>(j)];
    const internal::JointWorld jw = internal::JointInWorld(model_, joint);
    if (joint.actuated) {
      throw std::invalid_argument("joint '" + joint.name + "': an actuated joint that closes a loop cannot be written to "
                                  "MJCF (an equality has no actuator); make another joint of its loop the cut");
    }
    switch (joint.type) {
      case JointType::kSpherical:
        equalities_.push_back({Connect(joint.name, joint.body_a, joint.body_b, jw.point)});
        return;
      case JointType::kRevolute:
        equalities_.push_back({Connect(joint.name, joint.body_a, joint.body_b, jw.point)});
        equalities_.push_back({Connect(names_.Claim(joint.name + "_2"), joint.body_a, joint.body_b,
                                       jw.point + kMjcfAnchorSpacing * jw.axis.normalized())});
        return;
      case JointType::kFixed: {
        const int first = joint.body_a == kWorld ? joint.body_b : joint.body_a;
        const int second = joint.body_a == kWorld ? joint.body_a : joint.body_b;
        equalities_.push_back({"<weld name=\"" + joint.name + "\" body1=\"" + internal::BodyName(model_, first) +
                               "\" body2=\"" + internal::BodyName(model_, second) + "\" solref=\"" + kMjcfSolref +
                               "\" solimp=\"" + kMjcfSolimp + "\"/>"});
        return;
      }
      case JointType::kPrismatic:
      case JointType::kUniversal:
        break;
    }
    throw std::invalid_argument("joint '" + joint.name + "': a loop of this model can only be cut at this " +
                                std::string(joint.type == JointType::kPrismatic ? "prismatic" : "universal") +
                                " joint, which no MuJoCo equality expresses exactly");
  }

  // One position actuator per control, in control order.
  void AddActuators() {
    for (const std::string& joint : control_joints_) actuators_.push_back({joint, joint});
    for (int j = 0; j < static_cast<int>(model_.joints.size()); ++j) {
      const auto it = actuated_tree_joints_.find(j);
      if (it != actuated_tree_joints_.end()) actuators_.push_back({model_.joints[j].name, it->second});
    }
  }

  void WriteBody(std::ostream& os, int body, const Eigen::Isometry3d& X_WP, const std::string& indent) const;
  std::string Text() const;

  const Model& model_;
  internal::NameSet names_;
  internal::SpanningTree tree_;
  std::vector<std::vector<MjcfJoint>> joints_of_;  // per body
  std::vector<std::vector<int>> children_;         // per body + 1 (0: world), tree order
  std::vector<MjcfEquality> equalities_;
  std::vector<std::string> control_joints_;        // the bases' joints, control order
  std::map<int, std::string> actuated_tree_joints_;  // model joint -> its MJCF joint
  std::vector<std::pair<std::string, std::string>> actuators_;  // (name, joint), control order
  std::string payload_name_ = names_.Claim("payload");
};

// <inertial> of a mass (body frame); a point mass gets a tiny sphere's
// moments (MuJoCo needs positive ones).
std::string Inertial(const MassProperties& m) {
  const Eigen::Matrix3d& I = m.inertia_B;
  const double floor = I.norm() > 0 ? 0.0 : kMjcfMinInertia;
  return "<inertial pos=\"" + Triple(m.com_B) + "\" mass=\"" + Number(m.mass) + "\" fullinertia=\"" +
         Number(I(0, 0) + floor) + " " + Number(I(1, 1) + floor) + " " + Number(I(2, 2) + floor) + " " +
         Number(I(0, 1)) + " " + Number(I(0, 2)) + " " + Number(I(1, 2)) + "\"/>";
}

void MjcfBuilder::WriteBody(std::ostream& os, int body, const Eigen::Isometry3d& X_WP,
                            const std::string& indent) const {
  const Body& b = model_.bodies[static_cast<std::size_t>(body)];
  const Eigen::Isometry3d X_WB = Home(body);
  const Eigen::Isometry3d X_PB = X_WP.inverse() * X_WB;
  os << indent << "<body name=\"" << b.name << "\" pos=\"" << Triple(X_PB.translation()) << "\" quat=\""
     << QuatText(X_PB.linear()) << "\">\n";
  const MassProperties& m = b.inertia;
  if (m.mass > 0) {
    os << indent << "  " << Inertial(m) << "\n";
  } else {
    os << indent << "  <inertial pos=\"0 0 0\" mass=\"" << Number(kMjcfMinMass) << "\" diaginertia=\""
       << Number(kMjcfMinInertia) << " " << Number(kMjcfMinInertia) << " " << Number(kMjcfMinInertia) << "\"/>\n";
  }
  for (const MjcfJoint& j : joints_of_[static_cast<std::size_t>(body)]) {
    os << indent << "  <joint name=\"" << j.name << "\" type=\"" << j.type << "\" pos=\"" << Triple(j.pos) << "\"";
    if (j.type != "ball") os << " axis=\"" << Triple(j.axis.normalized()) << "\" ref=\"" << Number(j.ref) << "\"";
    if (j.limited) os << " limited=\"true\" range=\"" << Number(j.lower) << " " << Number(j.upper) << "\"";
    os << " armature=\"" << Number(kMjcfArmature) << "\" damping=\"" << Number(kMjcfDamping) << "\"/>\n";
  }
  if (body == model_.end_effector.body) {
    os << indent << "  <site name=\"end_effector\" pos=\"" << Triple(model_.end_effector.p_B) << "\"/>\n";
    // The payload: a body welded to the end-effector's, with its mass.
    if (model_.end_effector.payload.mass > 0) {
      os << indent << "  <body name=\"" << payload_name_ << "\">\n"
         << indent << "    " << Inertial(model_.end_effector.payload) << "\n" << indent << "  </body>\n";
    }
  }
  for (const int child : children_[static_cast<std::size_t>(body) + 1]) WriteBody(os, child, X_WB, indent + "  ");
  os << indent << "</body>\n";
}

std::string MjcfBuilder::Text() const {
  std::ostringstream os;
  os << "<!-- " << model_.name << ", written by `ccma export`: bodies at the assembled home (qpos0), loops closed by\n"
     << "     the equalities, one position actuator per control (its value: its joint's qpos). -->\n"
     << "<mujoco model=\"" << model_.name << "\">\n"
     << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
     << "  <option timestep=\"" << Number(kMjcfTimestep) << "\" gravity=\"" << Triple(model_.gravity)
     << "\" integrator=\"implicit\"/>\n"
     << "  <size njmax=\"" << 100 + 6 * static_cast<int>(equalities_.size()) << "\" nconmax=\"100\"/>\n"
     << "  <worldbody>\n";
  if (model_.end_effector.body == kWorld) {
    os << "    <site name=\"end_effector\" pos=\"" << Triple(model_.end_effector.p_B) << "\"/>\n";
  }
  for (const int child : children_[0]) WriteBody(os, child, Eigen::Isometry3d::Identity(), "    ");
  os << "  </worldbody>\n";
  if (!equalities_.empty()) {
    os << "  <equality>\n";
    for (const MjcfEquality& e : equalities_) os << "    " << e.text << "\n";
    os << "  </equality>\n";
  }
  if (!actuators_.empty()) {
    os << "  <actuator>\n";
    for (const auto& [name, joint] : actuators_) {
      os << "    <position name=\"" << name << "\" joint=\"" << joint << "\" kp=\"" << Number(kMjcfActuatorKp)
         << "\"/>\n";
    }
    os << "  </actuator>\n";
  }
  // The keyframe: qpos0 in MuJoCo's order (bodies depth first, as written;
  // each body's joints in order), the controls at home.
  std::ostringstream qpos;
  std::vector<int> stack(children_[0].rbegin(), children_[0].rend());
  while (!stack.empty()) {
    const int body = stack.back();
    stack.pop_back();
    for (const MjcfJoint& j : joints_of_[static_cast<std::size_t>(body)]) {
      qpos << (qpos.tellp() > 0 ? " " : "") << (j.type == "ball" ? std::string("1 0 0 0") : Number(j.ref));
    }
    const std::vector<int>& children = children_[static_cast<std::size_t>(body) + 1];
    stack.insert(stack.end(), children.rbegin(), children.rend());
  }
  std::string ctrl;
  const Eigen::VectorXd u = model_.home_controls();
  for (Eigen::Index i = 0; i < u.size(); ++i) ctrl += (i ? " " : "") + Number(u[i]);
  os << "  <keyframe>\n    <key name=\"home\" qpos=\"" << qpos.str() << "\"" << (u.size() ? " ctrl=\"" + ctrl + "\"" : "")
     << "/>\n  </keyframe>\n</mujoco>\n";
  return os.str();
}

}  // namespace

MjcfExport WriteMjcf(const Model& model) { return MjcfBuilder(model).Build(); }

}  // namespace ccma
