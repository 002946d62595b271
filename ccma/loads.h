// The loads statics weighs (model_format.md, "Masses and loads"): gravity on
// every body's mass and on the payload, and an external wrench on the
// end-effector body, as one generalized force Q over the state tangent: per
// body [M; F], the moment about the body's origin and the force, world
// frame, the work conjugates of (dphi, dp) (state.h). Units: N, N*m.
#ifndef CCMA_CCMA_LOADS_H_
#define CCMA_CCMA_LOADS_H_

#include <vector>

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// On the end-effector body, world frame: a force at the end-effector point
// and a moment [N, N*m].
struct ExternalWrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
};

// Q (s.tangent_size()) at s: gravity on every mass and on the payload, and
// `wrench`.
Eigen::VectorXd GeneralizedLoads(const Model& model, const State& s, const ExternalWrench& wrench = {});

// dQ/ds (s.tangent_size() squared): how the loads' moments about the body
// origins turn with the bodies (the forces and the wrench's moment are fixed
// in the world). Analytic.
Eigen::MatrixXd GeneralizedLoadsJacobian(const Model& model, const State& s, const ExternalWrench& wrench = {});
// The same by its only nonzero blocks: per body b, the 3 x 3 block of its
// moment over its rotation, dQ[6b..6b+3) / dphi_b (num_bodies entries).
std::vector<Eigen::Matrix3d> GeneralizedLoadsJacobianBlocks(const Model& model, const State& s,
                                                            const ExternalWrench& wrench = {});

}  // namespace ccma

#endif  // CCMA_CCMA_LOADS_H_
