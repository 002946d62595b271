#include "ccma/internal/constraint_set.h"

#include "cost_functions/actuated_prismatic_cost.h"
#include "cost_functions/actuated_revolute_cost.h"
#include "cost_functions/body_frame.h"
#include "cost_functions/fixed_joint_cost.h"
#include "cost_functions/omni_base_motor_cost.h"
#include "cost_functions/omni_base_planar_cost.h"
#include "cost_functions/prismatic_joint_cost.h"
#include "cost_functions/revolute_joint_cost.h"
#include "cost_functions/spherical_joint_cost.h"
#include "cost_functions/universal_joint_cost.h"

namespace ccma {
namespace {

std::unique_ptr<ceres::CostFunction> MakeJointCost(const Joint& j) {
  switch (j.type) {
    case JointType::kRevolute:
      return std::make_unique<RevoluteJointCost>(j.p_A, j.p_B, j.a_A, j.a_B);
    case JointType::kSpherical:
      return std::make_unique<SphericalJointCost>(j.p_A, j.p_B);
    case JointType::kUniversal:
      return std::make_unique<UniversalJointCost>(j.p_A, j.p_B, j.a_A, j.b_B);
    case JointType::kPrismatic:
      return std::make_unique<PrismaticJointCost>(j.p_A, j.p_B, j.a_A, j.d1_A, j.d1_B,
                                                  j.d2_A, j.d2_B);
    case JointType::kFixed:
      return std::make_unique<FixedJointCost>(j.p_A, j.p_B, j.d1_A, j.d1_B, j.d2_A,
                                              j.d2_B);
  }
  return nullptr;
}

std::unique_ptr<ceres::CostFunction> MakeJointTwin(const Joint& j) {
  switch (j.type) {
    case JointType::kRevolute:
      return std::unique_ptr<ceres::CostFunction>(MakeRevoluteJointAutoDiff(j.p_A, j.p_B, j.a_A, j.a_B));
    case JointType::kSpherical:
      return std::unique_ptr<ceres::CostFunction>(MakeSphericalJointAutoDiff(j.p_A, j.p_B));
    case JointType::kUniversal:
      return std::unique_ptr<ceres::CostFunction>(MakeUniversalJointAutoDiff(j.p_A, j.p_B, j.a_A, j.b_B));
    case JointType::kPrismatic:
      return std::unique_ptr<ceres::CostFunction>(
          MakePrismaticJointAutoDiff(j.p_A, j.p_B, j.a_A, j.d1_A, j.d1_B, j.d2_A, j.d2_B));
    case JointType::kFixed:
      return std::unique_ptr<ceres::CostFunction>(
          MakeFixedJointAutoDiff(j.p_A, j.p_B, j.d1_A, j.d1_B, j.d2_A, j.d2_B));
  }
  return nullptr;
}

std::unique_ptr<ceres::CostFunction> MakeActuatorCost(const Joint& j) {
  if (j.type == JointType::kRevolute) return std::make_unique<ActuatedRevoluteCost>(j.e1_A, j.e2_A, j.w_B);
  return std::make_unique<ActuatedPrismaticCost>(j.p_A, j.p_B, j.a_A);
}

std::unique_ptr<ceres::CostFunction> MakeActuatorTwin(const Joint& j) {
  if (j.type == JointType::kRevolute) {
    return std::unique_ptr<ceres::CostFunction>(MakeActuatedRevoluteAutoDiff(j.e1_A, j.e2_A, j.w_B));
  }
  return std::unique_ptr<ceres::CostFunction>(MakeActuatedPrismaticAutoDiff(j.p_A, j.p_B, j.a_A));
}

// The ground's pose block: identity rotation, origin.
const double kWorldPose[kPoseAmbientSize] = {0, 0, 0, 1, 0, 0, 0};

}  // namespace

const double* ConstraintSet::Pose(const State& s, int body) {
  return body == kWorld ? kWorldPose : s.pose(body);
}

std::vector<std::unique_ptr<ceres::CostFunction>> ConstraintSet::MakeAutoDiffTwins(
    const Model& model) const {
  std::vector<std::unique_ptr<ceres::CostFunction>> twins;
  for (const Joint& joint : model.joints) {
    twins.push_back(MakeJointTwin(joint));
    if (joint.actuated) twins.push_back(MakeActuatorTwin(joint));
  }
  for (int k = 0; k < model.num_bases(); ++k) {
    twins.emplace_back(MakeOmniBasePlanarAutoDiff());
    twins.emplace_back(MakeOmniBaseMotorAutoDiff());
  }
  return twins;
}

ConstraintSet::ConstraintSet(const Model& model)
    : state_size_(model.state_size()), num_controls_(model.num_controls()) {
  auto add = [this](std::unique_ptr<ceres::CostFunction> cost, std::vector<int> bodies,
                    int control_offset, int control_size, std::string label) {
    ConstraintBlock block;
    block.rows = cost->num_residuals();
    block.second_order = dynamic_cast<const ResidualHessian*>(cost.get());
    block.cost = std::move(cost);
    block.bodies = std::move(bodies);
    block.control_offset = control_offset;
    block.control_size = control_size;
    block.row = num_rows_;
    block.label = std::move(label);
    num_rows_ += block.rows;
    blocks_.push_back(std::move(block));
  };
  for (size_t j = 0; j < model.joints.size(); ++j) {
    const Joint& joint = model.joints[j];
    auto name = [&](int body) { return body == kWorld ? std::string("world") : model.bodies[body].name; };
    const std::string label = "joints[" + std::to_string(j) + "] " + joint.name + " (" +
                              JointTypeName(joint.type) + " " + name(joint.body_a) + "-" + name(joint.body_b) + ")";
    add(MakeJointCost(joint), {joint.body_a, joint.body_b}, -1, 0, label);
    if (joint.actuated) add(MakeActuatorCost(joint), {joint.body_a, joint.body_b}, joint.control, 1, label + " motor");
  }
  for (int k = 0; k < model.num_bases(); ++k) {
    const MobileBase& base = model.mobile_bases[k];
    add(std::make_unique<OmniBasePlanarCost>(), {base.body}, -1, 0, base.name + " (planar)");
    add(std::make_unique<OmniBaseMotorCost>(), {base.body}, kBaseControlSize * k, kBaseControlSize,
        base.name + " (motor)");
  }
}

void ConstraintSet::Evaluate(const State& s, const Eigen::VectorXd& u, Eigen::VectorXd* C,
                             Eigen::MatrixXd* J_s, Eigen::MatrixXd* J_u) const {
  C->resize(num_rows_);
  // Every block writes the same entries each time and nothing else, so the
  // rest only needs zeroing when the matrix is (re)allocated: a workspace
  // reused across calls (the control loop's) is neither reallocated nor cleared.
  if (J_s != nullptr && (J_s->rows() != num_rows_ || J_s->cols() != state_size_)) {
    J_s->setZero(num_rows_, state_size_);
  }
  if (J_u != nullptr && (J_u->rows() != num_rows_ || J_u->cols() != num_controls_)) {
    J_u->setZero(num_rows_, num_controls_);
  }
  // Scratch for one block: at most kMaxRows rows x 7 columns per parameter block.
  constexpr int kMaxRows = 9;
  double jac_storage[3][kMaxRows * kPoseAmbientSize];
  std::vector<const double*> params;
  for (const ConstraintBlock& block : blocks_) {
    params.clear();
    for (int body : block.bodies) params.push_back(Pose(s, body));
    if (block.control_size > 0) params.push_back(u.data() + block.control_offset);
    double* jacobians[3] = {jac_storage[0], jac_storage[1], jac_storage[2]};
    const bool want_jacobians = J_s != nullptr || J_u != nullptr;
    block.cost->Evaluate(params.data(), C->data() + block.row,
                         want_jacobians ? jacobians : nullptr);
    if (!want_jacobians) continue;
    for (size_t p = 0; p < block.bodies.size(); ++p) {
      if (J_s == nullptr) break;
      if (block.bodies[p] == kWorld) continue;  // the ground is not in the state
      const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, kPoseAmbientSize, Eigen::RowMajor>> J(
          jac_storage[p], block.rows, kPoseAmbientSize);
      J_s->block(block.row, kPoseTangentSize * block.bodies[p], block.rows, kPoseTangentSize) =
          J.leftCols<kPoseTangentSize>();
    }
    if (block.control_size > 0 && J_u != nullptr) {
      using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
      J_u->block(block.row, block.control_offset, block.rows, block.control_size) =
          Eigen::Map<const RowMajor>(jac_storage[block.bodies.size()], block.rows, block.control_size);
    }
  }
}

void ConstraintSet::EvaluateDerivatives(const State& s, const Eigen::VectorXd& u,
                                        EnergyDerivatives* out) const {
  Evaluate(s, u, &out->C, &out->J_s, &out->J_u);
  const int n = state_size_;
  out->energy = 0.5 * out->C.squaredNorm();
  out->G.noalias() = out->J_s.transpose() * out->C;
  out->dE_du.noalias() = out->J_u.transpose() * out->C;
  out->H.setZero(n, n);
  out->dG_du.setZero(n, num_controls_);
  Eigen::MatrixXd local(12, 12);
  std::vector<const double*> params;
  for (const ConstraintBlock& block : blocks_) {
    const int rows = block.rows;
    const int poses = static_cast<int>(block.bodies.size());
    // J^T J over the (at most two) bodies this block touches.
    for (int a = 0; a < poses; ++a) {
      if (block.bodies[a] == kWorld) continue;
      const auto J_a = out->J_s.block(block.row, 6 * block.bodies[a], rows, 6);
      for (int b = 0; b < poses; ++b) {
        if (block.bodies[b] == kWorld) continue;
        const auto J_b = out->J_s.block(block.row, 6 * block.bodies[b], rows, 6);
        out->H.block<6, 6>(6 * block.bodies[a], 6 * block.bodies[b]).noalias() += J_a.transpose() * J_b;
      }
      if (block.control_size > 0) {
        out->dG_du.block(6 * block.bodies[a], block.control_offset, 6, block.control_size).noalias() +=
            J_a.transpose() * out->J_u.block(block.row, block.control_offset, rows, block.control_size);
      }
    }
    // sum_i C_i Hess(C_i).
    params.clear();
    for (int body : block.bodies) params.push_back(Pose(s, body));
    if (block.control_size > 0) params.push_back(u.data() + block.control_offset);
    local.setZero();
    block.second_order->AddWeightedHessian(params.data(), out->C.data() + block.row,
                                           local.topLeftCorner(6 * poses, 6 * poses));
    for (int a = 0; a < poses; ++a) {
      for (int b = 0; b < poses; ++b) {
        if (block.bodies[a] == kWorld || block.bodies[b] == kWorld) continue;
        out->H.block<6, 6>(6 * block.bodies[a], 6 * block.bodies[b]) += local.block<6, 6>(6 * a, 6 * b);
      }
    }
  }
}

double ConstraintSet::Energy(const State& s, const Eigen::VectorXd& u) const {
  Eigen::VectorXd C;
  Evaluate(s, u, &C);
  return 0.5 * C.squaredNorm();
}

}  // namespace ccma
