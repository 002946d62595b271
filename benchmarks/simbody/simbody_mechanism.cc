#include "benchmarks/simbody/simbody_mechanism.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Geometry>
#include <Eigen/QR>

#include "benchmarks/simbody/base_track_motion.h"

namespace ccma::simbody_benchmark {
namespace {

SimTK::Vec3 ToVec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// R must be a rotation to rounding (the model's frames are built as such).
SimTK::Rotation ToRotation(const Eigen::Matrix3d& R) {
  SimTK::Mat33 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = R(i, j);
  return SimTK::Rotation(m, true);
}

// A pose (R_WX, p_WX) of some frame X in world.
struct Pose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
};

Pose HomePose(const Model& model, int body) {
  if (body == kWorld) return {};
  return {model.bodies[body].R_WB_home, model.bodies[body].p_WB_home};
}

// X_BJ: the frame J (given in world at home) seen from body B's frame.
SimTK::Transform InBody(const Pose& X_WB, const Pose& X_WJ) {
  return SimTK::Transform(ToRotation(X_WB.R.transpose() * X_WJ.R), ToVec3(X_WB.R.transpose() * (X_WJ.p - X_WB.p)));
}

// The joint frame J in world at home: origin at the joint point; for a
// revolute its z is the axis (x the model's reference direction e1), for a
// universal x is the first axis and y the second (parent first: Simbody's
// Universal turns about F's x, then about the new y).
Pose JointFrame(const Model& model, const Joint& j, bool a_is_parent) {
  const Pose A = HomePose(model, j.body_a), B = HomePose(model, j.body_b);
  Pose J;
  J.p = A.R * j.p_A + A.p;
  if (j.type == JointType::kRevolute) {
    const Eigen::Vector3d z = A.R * j.a_A, x = A.R * j.e1_A;
    J.R.col(0) = x;
    J.R.col(1) = z.cross(x);
    J.R.col(2) = z;
  } else if (j.type == JointType::kUniversal) {
    const Eigen::Vector3d a = A.R * j.a_A, b = B.R * j.b_B;
    const Eigen::Vector3d x = a_is_parent ? a : b, y = a_is_parent ? b : a;
    J.R.col(0) = x;
    J.R.col(1) = y;
    J.R.col(2) = x.cross(y);
  }
  return J;
}

void CheckSupported(const Joint& j) {
  if (j.actuated) throw std::runtime_error("joint '" + j.name + "': actuated joints are not modelled in Simbody here");
  if (j.type == JointType::kPrismatic)
    throw std::runtime_error("joint '" + j.name + "': prismatic joints are not modelled in Simbody here");
}

}  // namespace

SimbodyMechanism::SimbodyMechanism(const Model& model, std::shared_ptr<const std::vector<Eigen::VectorXd>> controls)
    : model_(model), matter_(system_), mobods_(model.bodies.size()) {
  const SimTK::Body::Rigid body_info(SimTK::MassProperties(1.0, SimTK::Vec3(0), SimTK::UnitInertia(1.0)));
  SimTK::MobilizedBody& ground = matter_.updGround();
  std::vector<bool> in_tree(model.bodies.size(), false);
  auto mobod = [&](int body) -> SimTK::MobilizedBody& { return body == kWorld ? ground : mobods_[body]; };
  auto placed = [&](int body) { return body == kWorld || in_tree[body]; };

  // Bases: Planar on Ground, frames at the world and body origins, so
  // q = (theta, x, y) is exactly the base's controls (model.h).
  for (int b = 0; b < model.num_bases(); ++b) {
    const int body = model.mobile_bases[b].body;
    SimTK::MobilizedBody::Planar planar(ground, SimTK::Transform(), body_info, SimTK::Transform());
    SimTK::Motion::Custom(planar, new BaseTrackMotion(controls, b));
    mobods_[body] = planar;
    in_tree[body] = true;
  }

  // Spanning tree: passes over the joints in file order until none joins a
  // new body.
  std::vector<bool> is_tree_joint(model.joints.size(), false);
  for (bool grown = true; grown;) {
    grown = false;
    for (size_t i = 0; i < model.joints.size(); ++i) {
      const Joint& j = model.joints[i];
      if (is_tree_joint[i] || placed(j.body_a) == placed(j.body_b)) continue;
      CheckSupported(j);
      const bool a_is_parent = placed(j.body_a);
      const int parent = a_is_parent ? j.body_a : j.body_b, child = a_is_parent ? j.body_b : j.body_a;
      const Pose X_WJ = JointFrame(model, j, a_is_parent);
      const SimTK::Transform X_PF = InBody(HomePose(model, parent), X_WJ);
      const SimTK::Transform X_CM = InBody(HomePose(model, child), X_WJ);
      SimTK::MobilizedBody& P = mobod(parent);
      switch (j.type) {
        case JointType::kRevolute: mobods_[child] = SimTK::MobilizedBody::Pin(P, X_PF, body_info, X_CM); break;
        case JointType::kSpherical: mobods_[child] = SimTK::MobilizedBody::Ball(P, X_PF, body_info, X_CM); break;
        case JointType::kUniversal:
          mobods_[child] = SimTK::MobilizedBody::Universal(P, X_PF, body_info, X_CM);
          break;
        case JointType::kFixed: mobods_[child] = SimTK::MobilizedBody::Weld(P, X_PF, body_info, X_CM); break;
        case JointType::kPrismatic: break;  // rejected by CheckSupported
      }
      in_tree[child] = true;
      is_tree_joint[i] = true;
      grown = true;
      ++num_tree_joints_;
    }
  }
  for (size_t b = 0; b < in_tree.size(); ++b) {
    if (!in_tree[b]) throw std::runtime_error("body '" + model.bodies[b].name + "' is not connected to a base or the ground");
  }

  // Loop closures: the joints left over.
  for (size_t i = 0; i < model.joints.size(); ++i) {
    if (is_tree_joint[i]) continue;
    const Joint& j = model.joints[i];
    CheckSupported(j);
    SimTK::MobilizedBody& A = mobod(j.body_a);
    SimTK::MobilizedBody& B = mobod(j.body_b);
    if (j.type == JointType::kFixed) {
      const Pose X_WJ = JointFrame(model, j, true);
      SimTK::Constraint::Weld(A, InBody(HomePose(model, j.body_a), X_WJ), B, InBody(HomePose(model, j.body_b), X_WJ));
      num_constraint_equations_ += 6;
    } else {
      SimTK::Constraint::Ball(A, ToVec3(j.p_A), B, ToVec3(j.p_B));
      num_constraint_equations_ += 3;
      if (j.type == JointType::kRevolute) {
        // a_B stays perpendicular to e1_A and e2_A, i.e. parallel to a_A.
        angle_constraints_.push_back(
            SimTK::Constraint::ConstantAngle(A, SimTK::UnitVec3(ToVec3(j.e1_A)), B, SimTK::UnitVec3(ToVec3(j.a_B))));
        angle_constraints_.push_back(
            SimTK::Constraint::ConstantAngle(A, SimTK::UnitVec3(ToVec3(j.e2_A)), B, SimTK::UnitVec3(ToVec3(j.a_B))));
        num_constraint_equations_ += 2;
      } else if (j.type == JointType::kUniversal) {
        angle_constraints_.push_back(
            SimTK::Constraint::ConstantAngle(A, SimTK::UnitVec3(ToVec3(j.a_A)), B, SimTK::UnitVec3(ToVec3(j.b_B))));
        num_constraint_equations_ += 1;
      }
    }
    ++num_loop_joints_;
  }
  system_.realizeTopology();
}

int SimbodyMechanism::DisableRedundantAngleConstraints(SimTK::State* state, int* remaining_redundant) const {
  // The free q's: every q but the bases' (prescribed).
  std::vector<bool> is_free;
  auto rank_and_rows = [&](int* rows) {
    system_.realize(*state, SimTK::Stage::Time);
    system_.prescribeQ(*state);
    system_.realize(*state, SimTK::Stage::Position);
    if (is_free.empty()) {
      is_free.assign(state->getNQ(), true);
      for (const MobileBase& base : model_.mobile_bases) {
        const SimTK::MobilizedBody& m = mobods_[base.body];
        for (int i = 0; i < m.getNumQ(*state); ++i) is_free[m.getFirstQIndex(*state) + i] = false;
      }
    }
    SimTK::Matrix Pq;
    matter_.calcPq(*state, Pq);  // d(position errors)/dq, enabled constraints only
    Eigen::MatrixXd J(Pq.nrow(), std::count(is_free.begin(), is_free.end(), true));
    for (int r = 0; r < Pq.nrow(); ++r)
      for (int c = 0, col = 0; c < Pq.ncol(); ++c)
        if (is_free[c]) J(r, col++) = Pq(r, c);
    *rows = static_cast<int>(J.rows());
    if (J.size() == 0) return 0;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(J);
    qr.setThreshold(1e-10);  // relative to the largest pivot; rows are O(1) (m, cos)
    return static_cast<int>(qr.rank());
  };
  int rows = 0;
  const int rank = rank_and_rows(&rows);
  int disabled = 0;
  for (const SimTK::Constraint& c : angle_constraints_) {
    if (rows == rank) break;
    c.disable(*state);
    int rows_without = 0;
    if (rank_and_rows(&rows_without) == rank) {
      rows = rows_without;
      ++disabled;
    } else {
      c.enable(*state);
    }
  }
  rank_and_rows(&rows);  // leave the state realized with the final set
  if (remaining_redundant) *remaining_redundant = rows - rank;
  return disabled;
}

SimTK::State SimbodyMechanism::HomeState() const {
  SimTK::State state = system_.getDefaultState();
  state.setTime(0);
  system_.realizeModel(state);
  return state;
}

Eigen::Vector3d SimbodyMechanism::EndEffectorPosition(const SimTK::State& state) const {
  const SimTK::Vec3 p_WE = mobods_[model_.end_effector.body].findStationLocationInGround(
      state, ToVec3(model_.end_effector.p_B));
  return {p_WE[0], p_WE[1], p_WE[2]};
}

}  // namespace ccma::simbody_benchmark
