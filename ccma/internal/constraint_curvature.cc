// ConstraintSet::CurvatureAlong (constraint_set.h): the second derivative of
// C along a motion of the state and the controls, block by block from the
// analytic second-order terms the exact Hessian of E already uses
// (FramedCost::AddWeightedHessianInFrames, one unit weight per row) and the
// motors' control curvature (FramedCost::AddControlCurvature).
#include "ccma/internal/constraint_set.h"

namespace ccma {

void ConstraintSet::CurvatureAlong(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& ds,
                                   const Eigen::VectorXd& du, Eigen::VectorXd* h, BodyFrames* frames) const {
  constexpr int kT = kPoseTangentSize;
  ComputeFrames(s, frames);
  h->setZero(num_rows_);
  const double* params[3] = {nullptr, nullptr, nullptr};
  const BodyFrame* block_frames[2];
  Eigen::Matrix<double, 2 * kT, 2 * kT> local;
  Eigen::Matrix<double, 2 * kT, 1> motion;  // ds over the block's pose blocks (the ground's: zero)
  Eigen::Matrix<double, 9, 1> unit;         // a block has at most 9 rows (constructor)
  for (const ConstraintBlock& block : blocks_) {
    const int poses = block.num_poses, size = kT * poses;
    for (int p = 0; p < poses; ++p) {
      const int body = block.bodies[static_cast<size_t>(p)];
      params[p] = Pose(s, body);
      motion.segment<kT>(kT * p) = body == kWorld ? Eigen::Matrix<double, kT, 1>::Zero().eval()
                                                  : ds.segment<kT>(kT * body).eval();
    }
    params[poses] = block.control_size > 0 ? u.data() + block.control_offset : nullptr;
    BlockFrames(block, *frames, block_frames);
    for (int r = 0; r < block.rows; ++r) {
      unit.setZero();
      unit[r] = 1.0;
      local.setZero();
      block.framed->AddWeightedHessianInFrames(block_frames, params, unit.data(), local.topLeftCorner(size, size));
      (*h)[block.row + r] = motion.head(size).dot(local.topLeftCorner(size, size) * motion.head(size));
    }
    if (block.control_size > 0) {
      block.framed->AddControlCurvature(params, du.data() + block.control_offset, h->data() + block.row);
    }
  }
}

}  // namespace ccma
