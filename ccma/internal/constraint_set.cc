#include "ccma/internal/constraint_set.h"

#include <algorithm>
#include <stdexcept>

#include "cost_functions/actuated_prismatic_cost.h"
#include "cost_functions/actuated_revolute_cost.h"
#include "cost_functions/body_frame.h"
#include "cost_functions/fixed_joint_cost.h"
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

std::unique_ptr<ceres::CostFunction> MakeActuatorCost(const Joint& j) {
  if (j.type == JointType::kRevolute) return std::make_unique<ActuatedRevoluteCost>(j.e1_A, j.e2_A, j.w_B, j.q_home);
  return std::make_unique<ActuatedPrismaticCost>(j.p_A, j.p_B, j.a_A, j.q_home);
}

}  // namespace

const double ConstraintSet::kWorldPose[kPoseAmbientSize] = {0, 0, 0, 1, 0, 0, 0};

ConstraintSet::ConstraintSet(const Model& model)
    : state_size_(model.state_size()), num_controls_(model.num_controls()) {
  auto add = [this, &model](std::unique_ptr<ceres::CostFunction> cost, std::vector<int> bodies,
                            int control_offset, int control_size, std::string label) {
    ConstraintBlock block;
    block.num_poses = static_cast<int>(bodies.size());
    for (size_t p = 0; p < bodies.size(); ++p) block.frames[p] = bodies[p] == kWorld ? model.num_bodies() : bodies[p];
    block.rows = cost->num_residuals();
    block.framed = dynamic_cast<const FramedCost*>(cost.get());
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
  int control = 0;
  for (const MobileBase& base : model.mobile_bases) {
    const BaseKind& kind = KindOf(base);
    for (BaseConstraint& c : kind.Constraints(base, /*autodiff=*/false)) {
      add(std::move(c.cost), {base.body}, c.reads_controls ? control : -1, c.reads_controls ? kind.num_controls() : 0,
          base.name + " (" + c.part + ")");
    }
    control += kind.num_controls();
  }
  for (const ConstraintBlock& block : blocks_) {
    // The fixed-size scratch of EvaluateDerivatives and Energy relies on these bounds.
    if (block.rows > 9 || block.bodies.size() > 2 || block.control_size > kMaxBaseControls) {
      throw std::logic_error("ConstraintSet: block " + block.label + " exceeds 9 rows, 2 bodies or " +
                             std::to_string(kMaxBaseControls) + " controls");
    }
  }
  BuildPatterns();
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

namespace {

// Index of entry (row, col) in a compressed matrix's value array (the entry
// must be in the pattern). Constructor-time only: a binary search.
template <typename Sparse>
int ValueIndex(const Sparse& M, int row, int col) {
  const bool row_major = Sparse::IsRowMajor;
  const int outer = row_major ? row : col;
  const int inner = row_major ? col : row;
  const auto* begin = M.innerIndexPtr() + M.outerIndexPtr()[outer];
  const auto* end = M.innerIndexPtr() + M.outerIndexPtr()[outer + 1];
  const auto* it = std::lower_bound(begin, end, inner);
  if (it == end || *it != inner) throw std::logic_error("ConstraintSet: entry outside the derivative pattern");
  return static_cast<int>(it - M.innerIndexPtr());
}

template <typename Sparse>
Sparse PatternOf(int rows, int cols, std::vector<Eigen::Triplet<double>>* entries) {
  Sparse M(rows, cols);
  M.setFromTriplets(entries->begin(), entries->end(), [](double a, double) { return a; });
  M.makeCompressed();
  M.coeffs().setZero();
  return M;
}

}  // namespace

void ConstraintSet::BuildPatterns() {
  constexpr int kT = kPoseTangentSize;
  std::vector<Eigen::Triplet<double>> J_s, J_u, H, dG_du;
  auto add_block = [](std::vector<Eigen::Triplet<double>>* to, int row, int col, int rows, int cols) {
    for (int i = 0; i < rows; ++i) {
      for (int j = 0; j < cols; ++j) to->emplace_back(row + i, col + j, 1.0);
    }
  };
  for (int body = 0; body < state_size_ / kT; ++body) add_block(&H, kT * body, kT * body, kT, kT);
  for (const ConstraintBlock& block : blocks_) {
    for (int a : block.bodies) {
      if (a == kWorld) continue;
      add_block(&J_s, block.row, kT * a, block.rows, kT);
      for (int b : block.bodies) {
        if (b != kWorld) add_block(&H, kT * a, kT * b, kT, kT);
      }
      if (block.control_size > 0) add_block(&dG_du, kT * a, block.control_offset, kT, block.control_size);
    }
    if (block.control_size > 0) add_block(&J_u, block.row, block.control_offset, block.rows, block.control_size);
  }
  J_s_pattern_ = PatternOf<SparseRowMajor>(num_rows_, state_size_, &J_s);
  J_u_pattern_ = PatternOf<SparseRowMajor>(num_rows_, num_controls_, &J_u);
  H_pattern_ = PatternOf<SparseColMajor>(state_size_, state_size_, &H);
  dG_du_pattern_ = PatternOf<SparseColMajor>(state_size_, num_controls_, &dG_du);

  offsets_.assign(blocks_.size(), BlockOffsets());
  for (size_t k = 0; k < blocks_.size(); ++k) {
    const ConstraintBlock& block = blocks_[k];
    BlockOffsets& o = offsets_[k];
    const int first_row = J_s_pattern_.outerIndexPtr()[block.row];
    o.J_s_row_stride = J_s_pattern_.outerIndexPtr()[block.row + 1] - first_row;
    for (size_t p = 0; p < block.bodies.size(); ++p) {
      const int a = block.bodies[p];
      if (a == kWorld) continue;
      o.J_s[p] = ValueIndex(J_s_pattern_, block.row, kT * a);
      for (size_t q = 0; q < block.bodies.size(); ++q) {
        const int b = block.bodies[q];
        if (b == kWorld) continue;
        o.H[p][q] = ValueIndex(H_pattern_, kT * a, kT * b);
        o.H_column_stride[q] = H_pattern_.outerIndexPtr()[kT * b + 1] - H_pattern_.outerIndexPtr()[kT * b];
      }
      for (int c = 0; c < block.control_size; ++c) {
        o.dG_du[p].push_back(ValueIndex(dG_du_pattern_, kT * a, block.control_offset + c));
      }
    }
    if (block.control_size > 0) o.J_u = ValueIndex(J_u_pattern_, block.row, block.control_offset);
  }
}

namespace {

// Everything one block adds to EnergyDerivatives once its cost function has
// been evaluated, with the row count a template argument: J_p^T J_q is then
// a fixed-size coefficient-wise product (6 x Rows by Rows x 6), unrolled and
// vectorised. (A run-time row count made Eigen loop coefficient by
// coefficient; a plain `*` sends sizes with 6 + 6 + Rows > 20 to its blocked
// matrix product, whose packing costs more than the arithmetic.)
// `jacobians`: Rows x 7 row-major per pose, then Rows x control_size;
// `local`: the block's second-order terms (6 x 6 per pair of poses).
struct BlockTargets {
  double* J_s;
  double* J_u;
  double* H;
  double* dG_du;
  Eigen::VectorXd* G;
  Eigen::VectorXd* dE_du;
};

template <int Rows>
void AccumulateBlock(const ConstraintBlock& block, const ConstraintSet::BlockOffsets& o,
                     double* const jacobians[3], const double* C,
                     const Eigen::Matrix<double, 2 * kPoseTangentSize, 2 * kPoseTangentSize>& local,
                     const BlockTargets& out) {
  constexpr int kT = kPoseTangentSize;
  using AmbientJacobian = Eigen::Matrix<double, Rows, kPoseAmbientSize, Eigen::RowMajor>;
  using TangentJacobian = Eigen::Matrix<double, Rows, kT>;
  const Eigen::Map<const Eigen::Matrix<double, Rows, 1>> C_block(C);
  const int poses = static_cast<int>(block.bodies.size());
  TangentJacobian J_body[2];
  for (int p = 0; p < poses; ++p) {
    if (block.bodies[p] == kWorld) continue;
    J_body[p] = Eigen::Map<const AmbientJacobian>(jacobians[p]).template leftCols<kT>();
    for (int r = 0; r < Rows; ++r) {
      Eigen::Map<Eigen::Matrix<double, 1, kT>>(out.J_s + o.J_s[p] + r * o.J_s_row_stride) = J_body[p].row(r);
    }
    out.G->segment<kT>(kT * block.bodies[p]).noalias() += J_body[p].transpose() * C_block;
  }
  using ControlJacobian = Eigen::Matrix<double, Rows, Eigen::Dynamic, Eigen::RowMajor, Rows, kMaxBaseControls>;
  ControlJacobian J_control;
  if (block.control_size > 0) {
    J_control = Eigen::Map<const ControlJacobian>(jacobians[poses], Rows, block.control_size);
    Eigen::Map<ControlJacobian>(out.J_u + o.J_u, Rows, block.control_size) = J_control;
    out.dE_du->segment(block.control_offset, block.control_size).noalias() += J_control.transpose() * C_block;
  }
  for (int p = 0; p < poses; ++p) {
    if (block.bodies[p] == kWorld) continue;
    for (int q = 0; q < poses; ++q) {
      if (block.bodies[q] == kWorld) continue;
      const Eigen::Matrix<double, kT, kT> H_pq =
          J_body[p].transpose().lazyProduct(J_body[q]) + local.template block<kT, kT>(kT * p, kT * q);
      // Column-major 6 x 6 block: column c of body q starts H_column_stride apart.
      for (int c = 0; c < kT; ++c) {
        Eigen::Map<Eigen::Matrix<double, kT, 1>>(out.H + o.H[p][q] + c * o.H_column_stride[q]) += H_pq.col(c);
      }
    }
    for (int c = 0; c < block.control_size; ++c) {
      Eigen::Map<Eigen::Matrix<double, kT, 1>>(out.dG_du + o.dG_du[p][c]).noalias() +=
          J_body[p].transpose() * J_control.col(c);
    }
  }
}

}  // namespace

void ConstraintSet::EvaluateDerivatives(const State& s, const Eigen::VectorXd& u,
                                        EnergyDerivatives* out) const {
  constexpr int kT = kPoseTangentSize;
  constexpr int kMaxRows = 9;  // the largest block (cost_functions/)
  // Reused workspaces keep their patterns: only the values are overwritten.
  if (out->H.nonZeros() != H_pattern_.nonZeros() || out->H.rows() != state_size_) {
    out->J_s = J_s_pattern_;
    out->J_u = J_u_pattern_;
    out->H = H_pattern_;
    out->dG_du = dG_du_pattern_;
  }
  out->C.resize(num_rows_);
  out->G.setZero(state_size_);
  out->dE_du.setZero(num_controls_);
  out->H.coeffs().setZero();
  out->dG_du.coeffs().setZero();
  const BlockTargets targets{out->J_s.valuePtr(), out->J_u.valuePtr(), out->H.valuePtr(),
                             out->dG_du.valuePtr(), &out->G,          &out->dE_du};

  double jac_storage[3][kMaxRows * kPoseAmbientSize];
  Eigen::Matrix<double, 2 * kT, 2 * kT> local;
  const double* params[3];
  const BodyFrame* block_frames[2];
  ComputeFrames(s, &out->frames);
  for (size_t k = 0; k < blocks_.size(); ++k) {
    const ConstraintBlock& block = blocks_[k];
    const int poses = static_cast<int>(block.bodies.size());
    for (int p = 0; p < poses; ++p) params[p] = Pose(s, block.bodies[p]);
    if (block.control_size > 0) params[poses] = u.data() + block.control_offset;
    double* jacobians[3] = {jac_storage[0], jac_storage[1], jac_storage[2]};
    double* C = out->C.data() + block.row;
    BlockFrames(block, out->frames, block_frames);
    block.framed->EvaluateInFrames(block_frames, params, C, jacobians);
    // Local d2E over the block's bodies: J^T J (AccumulateBlock) plus
    // sum_i C_i Hess(C_i) (here).
    local.setZero();
    block.framed->AddWeightedHessianInFrames(block_frames, params, C, local.topLeftCorner(kT * poses, kT * poses));
    switch (block.rows) {
      case 1: AccumulateBlock<1>(block, offsets_[k], jacobians, C, local, targets); break;
      case 2: AccumulateBlock<2>(block, offsets_[k], jacobians, C, local, targets); break;
      case 3: AccumulateBlock<3>(block, offsets_[k], jacobians, C, local, targets); break;
      case 4: AccumulateBlock<4>(block, offsets_[k], jacobians, C, local, targets); break;
      case 5: AccumulateBlock<5>(block, offsets_[k], jacobians, C, local, targets); break;
      case 6: AccumulateBlock<6>(block, offsets_[k], jacobians, C, local, targets); break;
      case 7: AccumulateBlock<7>(block, offsets_[k], jacobians, C, local, targets); break;
      case 8: AccumulateBlock<8>(block, offsets_[k], jacobians, C, local, targets); break;
      default: AccumulateBlock<9>(block, offsets_[k], jacobians, C, local, targets); break;  // <= 9 (constructor)
    }
  }
  out->energy = 0.5 * out->C.squaredNorm();
}

void ConstraintSet::ComputeFrames(const State& s, BodyFrames* frames) const {
  const int bodies = state_size_ / kPoseTangentSize;
  if (frames->size() != size_t(bodies) + 1) {
    frames->resize(size_t(bodies) + 1);
    frames->back().Set(kWorldPose);  // the ground's, for kWorld
  }
  for (int b = 0; b < bodies; ++b) (*frames)[b].Update(s.pose(b));
}

double ConstraintSet::Energy(const State& s, const Eigen::VectorXd& u, BodyFrames* frames) const {
  // Block by block into a stack buffer: called on every solve by the
  // predictors, so nothing is allocated (no C vector, no parameter list).
  // The buffer is zeroed to its full fixed size so that the sum of squares
  // is one fixed-size (vectorised) reduction whatever the block's rows.
  // Only the control block is passed as a parameter: the frames carry the
  // poses (FramedCost).
  constexpr int kMaxRows = 9;  // the most rows of one block (a fixed joint)
  ComputeFrames(s, frames);
  Eigen::Matrix<double, kMaxRows, 1> residuals;
  const double* params[3] = {nullptr, nullptr, nullptr};
  const BodyFrame* block_frames[2];
  double sum = 0;
  for (const ConstraintBlock& block : blocks_) {
    params[block.num_poses] = block.control_size > 0 ? u.data() + block.control_offset : nullptr;
    BlockFrames(block, *frames, block_frames);
    residuals.setZero();
    block.framed->EvaluateInFrames(block_frames, params, residuals.data(), nullptr);
    sum += residuals.squaredNorm();
  }
  return 0.5 * sum;
}

double ConstraintSet::Energy(const State& s, const Eigen::VectorXd& u) const {
  BodyFrames frames;
  return Energy(s, u, &frames);
}

void ConstraintSet::AddWeightedHessian(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& w,
                                       Eigen::MatrixXd* H) const {
  BodyFrames frames;
  ComputeFrames(s, &frames);
  const double* params[3] = {nullptr, nullptr, nullptr};
  const BodyFrame* block_frames[2];
  Eigen::Matrix<double, 2 * kPoseTangentSize, 2 * kPoseTangentSize> local;
  for (const ConstraintBlock& block : blocks_) {
    if (w.segment(block.row, block.rows).isZero(0)) continue;
    const int poses = block.num_poses;
    for (int p = 0; p < poses; ++p) params[p] = Pose(s, block.bodies[p]);
    params[poses] = block.control_size > 0 ? u.data() + block.control_offset : nullptr;
    BlockFrames(block, frames, block_frames);
    local.setZero();
    const int size = kPoseTangentSize * poses;
    block.framed->AddWeightedHessianInFrames(block_frames, params, w.data() + block.row, local.topLeftCorner(size, size));
    for (int p = 0; p < poses; ++p) {
      for (int q = 0; q < poses; ++q) {
        const int a = block.bodies[p], b = block.bodies[q];
        if (a == kWorld || b == kWorld) continue;
        H->block<kPoseTangentSize, kPoseTangentSize>(kPoseTangentSize * a, kPoseTangentSize * b) +=
            local.block<kPoseTangentSize, kPoseTangentSize>(kPoseTangentSize * p, kPoseTangentSize * q);
      }
    }
  }
}

}  // namespace ccma
