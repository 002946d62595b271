// Kinematic primitives shared by ccma's analytic cost functions.
//
// A body's pose block is [q (4), p_WB (3)] (ccma/state.h). Its tangent
// increment is (dphi, dp) with R_WB <- Exp(dphi) R_WB, so for a body-fixed
// point r_B and direction v_B:
//   d(R r_B + p) / d(dphi) = -[R r_B]x,   d(R r_B + p) / d(dp) = I
//   d(R v_B)     / d(dphi) = -[R v_B]x,   d(R v_B)     / d(dp) = 0
// Jacobian blocks are Ceres row-major (rows x 7) with the lifted convention of
// ccma/internal/pose_manifold.h: tangent in columns 0-5, column 6 zero.
#ifndef CCMA_COST_FUNCTIONS_BODY_FRAME_H_
#define CCMA_COST_FUNCTIONS_BODY_FRAME_H_

#include <cstring>

#include <ceres/sized_cost_function.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ccma/rotation.h"
#include "ccma/state.h"

namespace ccma {

// Row-major Jacobian block of `Rows` residuals with respect to one pose block.
template <int Rows>
using PoseJacobian = Eigen::Map<Eigen::Matrix<double, Rows, 7, Eigen::RowMajor>>;

// The world pose of one body, read from its parameter block. The constraint
// set computes one per body and state and hands them to every joint the body
// is in (FramedCost::EvaluateInFrames), so each quaternion becomes a matrix
// once rather than once per joint.
struct BodyFrame {
  BodyFrame() = default;  // no rotation yet: for workspaces, filled by Set or Update
  explicit BodyFrame(const double* pose) { Set(pose); }
  void Set(const double* pose) {
    R_WB = Eigen::Map<const Eigen::Quaterniond>(pose).toRotationMatrix();
    std::memcpy(q_from, pose, sizeof(q_from));
    has_rotation = true;
    p_WB = Eigen::Map<const Eigen::Vector3d>(pose + 4);
  }
  // Set, for a workspace frame: the rotation is recomputed only when the
  // quaternion's bits changed since, which they do not when a formation
  // translates (a pure function of the pose, so the result is the same).
  void Update(const double* pose) {
    if (!has_rotation || std::memcmp(q_from, pose, sizeof(q_from)) != 0) {
      Set(pose);
    } else {
      p_WB = Eigen::Map<const Eigen::Vector3d>(pose + 4);
    }
  }
  // Body-fixed vector r_B in world axes (also the lever arm of a point).
  // Written out: Eigen's 3 x 3 product is an out-of-line call here.
  EIGEN_ALWAYS_INLINE Eigen::Vector3d Rotate(const Eigen::Vector3d& r_B) const {
    return {R_WB(0, 0) * r_B.x() + R_WB(0, 1) * r_B.y() + R_WB(0, 2) * r_B.z(),
            R_WB(1, 0) * r_B.x() + R_WB(1, 1) * r_B.y() + R_WB(1, 2) * r_B.z(),
            R_WB(2, 0) * r_B.x() + R_WB(2, 1) * r_B.y() + R_WB(2, 2) * r_B.z()};
  }

  Eigen::Matrix3d R_WB;
  Eigen::Vector3d p_WB;
  double q_from[4];           // the quaternion R_WB was computed from
  bool has_rotation = false;  // R_WB and q_from are set
};

// The same, for any scalar (ceres::Jet in the autodiff twins): the pose
// block's quaternion is normalised, so the twins differentiate the ambient
// parameters exactly as Ceres would for a plain AutoDiffCostFunction.
template <typename T>
struct BodyFrameT {
  explicit BodyFrameT(const T* pose)
      : R_WB(Eigen::Quaternion<T>(pose[3], pose[0], pose[1], pose[2]).normalized().toRotationMatrix()),
        p_WB(pose[4], pose[5], pose[6]) {}
  Eigen::Matrix<T, 3, 1> Rotate(const Eigen::Vector3d& v_B) const { return R_WB * v_B.cast<T>(); }
  Eigen::Matrix<T, 3, 1> Point(const Eigen::Vector3d& r_B) const { return Rotate(r_B) + p_WB; }

  Eigen::Matrix<T, 3, 3> R_WB;
  Eigen::Matrix<T, 3, 1> p_WB;
};

template <typename T>
using Vec3Map = Eigen::Map<Eigen::Matrix<T, 3, 1>>;

// Rows [row, row + 3) of r = (p_B - p_A) for body-fixed points r_A on body A
// and r_B on body B, and their Jacobian rows (either pointer may be null).
template <int Rows>
EIGEN_ALWAYS_INLINE void PointDifference(const BodyFrame& A, const Eigen::Vector3d& r_A,
                            const BodyFrame& B, const Eigen::Vector3d& r_B, int row,
                            double* residuals, double* jacobian_A, double* jacobian_B) {
  const Eigen::Vector3d lever_A = A.Rotate(r_A);
  const Eigen::Vector3d lever_B = B.Rotate(r_B);
  Eigen::Map<Eigen::Vector3d>(residuals + row) = (lever_B + B.p_WB) - (lever_A + A.p_WB);
  if (jacobian_A != nullptr) {
    PoseJacobian<Rows> J(jacobian_A);
    J.template block<3, 3>(row, 0) = Skew(lever_A);
    J.template block<3, 3>(row, 3) = -Eigen::Matrix3d::Identity();
  }
  if (jacobian_B != nullptr) {
    PoseJacobian<Rows> J(jacobian_B);
    J.template block<3, 3>(row, 0) = -Skew(lever_B);
    J.template block<3, 3>(row, 3) = Eigen::Matrix3d::Identity();
  }
}

// Rows [row, row + 3) of r = (v_B - v_A) for body-fixed directions v_A on A
// and v_B on B (world axes), and their Jacobian rows.
template <int Rows>
EIGEN_ALWAYS_INLINE void DirectionDifference(const BodyFrame& A, const Eigen::Vector3d& d_A,
                                const BodyFrame& B, const Eigen::Vector3d& d_B, int row,
                                double* residuals, double* jacobian_A, double* jacobian_B) {
  const Eigen::Vector3d v_A = A.Rotate(d_A);
  const Eigen::Vector3d v_B = B.Rotate(d_B);
  Eigen::Map<Eigen::Vector3d>(residuals + row) = v_B - v_A;
  if (jacobian_A != nullptr) {
    PoseJacobian<Rows>(jacobian_A).template block<3, 3>(row, 0) = Skew(v_A);
  }
  if (jacobian_B != nullptr) {
    PoseJacobian<Rows>(jacobian_B).template block<3, 3>(row, 0) = -Skew(v_B);
  }
}

// ---- Second order (exact Hessian of E = 1/2 C^T C, paper Section III-B) ----
// With R <- Exp(dphi) R, Exp(dphi) v = v + dphi x v + 1/2 dphi x (dphi x v) + ...,
// so the Hessian at dphi = 0 of the scalar w . (Exp(dphi) v) is
//   RotationHessian(w, v) = 1/2 (v w^T + w v^T) - (v . w) I.
// Translations enter linearly: no second-order terms of their own.
inline Eigen::Matrix3d RotationHessian(const Eigen::Vector3d& w, const Eigen::Vector3d& v) {
  return 0.5 * (v * w.transpose() + w * v.transpose()) - v.dot(w) * Eigen::Matrix3d::Identity();
}

// Dense Hessian over the stacked tangents of a cost's pose blocks: 6 per
// pose, [dphi_A, dp_A, dphi_B, dp_B].
using TangentHessian = Eigen::Ref<Eigen::MatrixXd>;

// Second-order terms of PointDifference / DirectionDifference rows weighted
// by w (both are w . (R_B x_B) - w . (R_A x_A) plus linear terms).
inline void AddDifferenceHessian(const BodyFrame& A, const Eigen::Vector3d& x_A, const BodyFrame& B,
                                 const Eigen::Vector3d& x_B, const Eigen::Vector3d& w,
                                 TangentHessian H) {
  H.block<3, 3>(0, 0) -= RotationHessian(w, A.Rotate(x_A));
  H.block<3, 3>(6, 6) += RotationHessian(w, B.Rotate(x_B));
}

// The interface the constraint set evaluates a ccma cost function through:
// at body frames computed once per body and state (frames[k] is the world
// pose of parameters[k], k over the cost's leading pose blocks; the rest of
// `parameters` are control blocks), with its second-order part. The poses
// are read from the frames only: their parameters[k] may be null.
class FramedCost {
 public:
  virtual ~FramedCost() = default;
  // Residuals and, if `jacobians` is non-null, the Jacobian blocks that
  // Evaluate would give (same layout, same null entries).
  virtual void EvaluateInFrames(const BodyFrame* const* frames, double const* const* parameters,
                                double* residuals, double** jacobians) const = 0;
  // Adds sum_k weights[k] * d^2 r_k / d(tangent)^2 into H (6 x 6 per pose
  // block, in parameter order; control blocks excluded: no ccma constraint
  // couples s and u at second order, so d^2 E / ds du = J_s^T J_u exactly).
  // With weights = C this is the term sum_i C_i Hess(C_i) of the exact
  // Hessian of E.
  virtual void AddWeightedHessianInFrames(const BodyFrame* const* frames, double const* const* parameters,
                                          const double* weights, TangentHessian H) const = 0;
  // The same from the parameters alone (frames computed here; tests).
  virtual void AddWeightedHessian(double const* const* parameters, const double* weights,
                                  TangentHessian H) const = 0;
  // Adds to out[k] (one per residual) d^2 r_k / dt^2 along the controls
  // u(t) = u + t du at t = 0, the poses held: the controls' own curvature,
  // which inverse dynamics needs beside the poses' (analyses/dynamics.h).
  // `parameters` as for Evaluate (the control block after the poses), `du`
  // the change of that control block. Zero for the costs that do not read
  // controls or read them linearly (the prismatic motor): the default.
  virtual void AddControlCurvature(double const* const* /*parameters*/, const double* /*du*/,
                                   double* /*out*/) const {}
};

namespace internal {
// How many of the leading parameter blocks are poses (1 or 2 for ccma's costs).
template <int... BlockSizes>
constexpr int LeadingPoseBlocks() {
  const int sizes[] = {BlockSizes..., 0};
  int n = 0;
  while (sizes[n] == kPoseAmbientSize) ++n;
  return n;
}
}  // namespace internal

// The base of every ccma cost function: its sizes are stated once, here in
// the template arguments (Rows residuals over parameter blocks of the given
// sizes, poses first), and read back as Cost::kNumResiduals by the
// constraint set, the model's row count and the autodiff twin. A cost
// implements the two *InFrames methods; Ceres' Evaluate computes the frames
// and calls them.
template <int Rows, int... BlockSizes>
class SizedCost : public ceres::SizedCostFunction<Rows, BlockSizes...>, public FramedCost {
 public:
  static constexpr int kNumResiduals = Rows;
  static constexpr int kNumPoses = internal::LeadingPoseBlocks<BlockSizes...>();
  static_assert(kNumPoses == 1 || kNumPoses == 2, "a ccma cost reads one or two poses, first");

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const final {
    const OwnFrames frames(parameters);
    EvaluateInFrames(frames.get(), parameters, residuals, jacobians);
    return true;
  }

  void AddWeightedHessian(double const* const* parameters, const double* weights, TangentHessian H) const final {
    const OwnFrames frames(parameters);
    AddWeightedHessianInFrames(frames.get(), parameters, weights, H);
  }

 private:
  // The frames of the kNumPoses pose blocks, built from the parameters (the
  // path of Ceres and of the tests; ccma's own solvers share theirs).
  class OwnFrames {
   public:
    explicit OwnFrames(double const* const* parameters) : A_(parameters[0]) {
      if constexpr (kNumPoses == 2) B_.Set(parameters[1]);
    }
    OwnFrames(const OwnFrames&) = delete;
    OwnFrames& operator=(const OwnFrames&) = delete;
    const BodyFrame* const* get() const { return pointers_; }

   private:
    BodyFrame A_, B_;  // B_ unset for one pose
    const BodyFrame* pointers_[2] = {&A_, &B_};
  };
};

// Zeroes a Jacobian block if it is requested (blocks are then filled sparsely).
template <int Rows>
inline void ZeroIfRequested(double* jacobian) {
  if (jacobian != nullptr) PoseJacobian<Rows>(jacobian).setZero();
}

// The jacobians[k] entry, or null when Ceres asked for no Jacobians at all.
inline double* JacobianOrNull(double** jacobians, int k) {
  return jacobians == nullptr ? nullptr : jacobians[k];
}

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_BODY_FRAME_H_
