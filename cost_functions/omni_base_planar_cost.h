// Planar constraint of an omnidirectional mobile base: the paper's C_planar.
//   r = [ z_B ;  R_WB e_z - e_z ]                     4 rows, 3 independent
// The base frame's origin stays on the ground (z = 0) and its normal stays
// vertical. Parameter: pose of the base body (7, state.h).
#ifndef CCMA_COST_FUNCTIONS_OMNI_BASE_PLANAR_COST_H_
#define CCMA_COST_FUNCTIONS_OMNI_BASE_PLANAR_COST_H_

#include <ceres/sized_cost_function.h>

#include "cost_functions/body_frame.h"

namespace ccma {

class OmniBasePlanarCost final : public SizedCost<4, kPoseAmbientSize> {
 public:

  void EvaluateInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/, double* residuals,
                        double** jacobians) const override {
    const BodyFrame& base = *frames[0];
    const Eigen::Vector3d n_W = base.R_WB.col(2);  // body normal in world
    residuals[0] = base.p_WB.z();
    Eigen::Map<Eigen::Vector3d>(residuals + 1) = n_W - Eigen::Vector3d::UnitZ();
    double* J_base = JacobianOrNull(jacobians, 0);
    if (J_base != nullptr) {
      PoseJacobian<kNumResiduals> J(J_base);
      J.setZero();
      J(0, 5) = 1.0;
      J.block<3, 3>(1, 0) = -Skew(n_W);
    }
  }

  void AddWeightedHessianInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/,
                                  const double* weights, TangentHessian H) const override {
    const BodyFrame& base = *frames[0];
    H.block<3, 3>(0, 0) += RotationHessian(Eigen::Map<const Eigen::Vector3d>(weights + 1), base.R_WB.col(2));
  }
};


// ---- Autodiff twin (tests and the Jacobian benchmark) ----
// The same residual, templated; ceres::AutoDiffCostFunction differentiates
// it with respect to the ambient parameters (quaternion, translation).
struct OmniBasePlanarResidual {
  template <typename T>
  bool operator()(const T* pose, T* r) const {
    const BodyFrameT<T> base(pose);
    r[0] = base.p_WB.z();
    Vec3Map<T>{r + 1} = base.R_WB.col(2) - Eigen::Vector3d::UnitZ().cast<T>();
    return true;
  }
};

// Defined in autodiff_twins.cc, the one file that instantiates the twins' Jet code.
ceres::CostFunction* MakeOmniBasePlanarAutoDiff();

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_OMNI_BASE_PLANAR_COST_H_
