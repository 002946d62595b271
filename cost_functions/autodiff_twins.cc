// The autodiff twins of ccma's analytic cost functions (cost_functions/*_cost.h
// declare them): each templated residual differentiated by
// ceres::AutoDiffCostFunction with the analytic cost's sizes. Only the tests,
// the Jacobian benchmark and `ccma bench` use them. Defined here, not inline in
// the headers: an inline factory makes every file that includes a cost header
// instantiate the twin's Jet code (9 of the 30 compiler seconds that
// constraint_set.cc's front end took; benchmarks/RESULTS.md, "The demo
// within 300 s").
#include <ceres/autodiff_cost_function.h>

#include "cost_functions/actuated_prismatic_cost.h"
#include "cost_functions/actuated_revolute_cost.h"
#include "cost_functions/fixed_joint_cost.h"
#include "cost_functions/legged_base_motor_cost.h"
#include "cost_functions/omni_base_motor_cost.h"
#include "cost_functions/omni_base_planar_cost.h"
#include "cost_functions/prismatic_joint_cost.h"
#include "cost_functions/revolute_joint_cost.h"
#include "cost_functions/spherical_joint_cost.h"
#include "cost_functions/universal_joint_cost.h"

namespace ccma {
namespace {

template <typename Functor, int Rows, int... BlockSizes>
ceres::CostFunction* AutoDiffTwinOf(const SizedCost<Rows, BlockSizes...>* /*sizes*/, Functor* functor) {
  return new ceres::AutoDiffCostFunction<Functor, Rows, BlockSizes...>(functor);
}

// The autodiff twin of the analytic cost `Cost`: the templated residual
// `functor` (owned by the result) with the same sizes, differentiated by Ceres
// with respect to the ambient parameters.
template <typename Cost, typename Functor>
ceres::CostFunction* MakeAutoDiffTwin(Functor* functor) {
  return AutoDiffTwinOf(static_cast<const Cost*>(nullptr), functor);
}

}  // namespace

ceres::CostFunction* MakeActuatedPrismaticAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B,
                                                   const Eigen::Vector3d& a_A, double q_home) {
  return MakeAutoDiffTwin<ActuatedPrismaticCost>(new ActuatedPrismaticResidual{r_A, r_B, a_A, q_home});
}

ceres::CostFunction* MakeActuatedRevoluteAutoDiff(const Eigen::Vector3d& e1_A, const Eigen::Vector3d& e2_A,
                                                  const Eigen::Vector3d& w_B, double q_home) {
  return MakeAutoDiffTwin<ActuatedRevoluteCost>(new ActuatedRevoluteResidual{e1_A, e2_A, w_B, q_home});
}

ceres::CostFunction* MakeFixedJointAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B, const Eigen::Vector3d& d1_A, const Eigen::Vector3d& d1_B, const Eigen::Vector3d& d2_A, const Eigen::Vector3d& d2_B) {
  return MakeAutoDiffTwin<FixedJointCost>(new FixedJointResidual{r_A, r_B, d1_A, d1_B, d2_A, d2_B});
}

ceres::CostFunction* MakeLeggedBaseMotorAutoDiff() {
  return MakeAutoDiffTwin<LeggedBaseMotorCost>(new LeggedBaseMotorResidual{});
}

ceres::CostFunction* MakeOmniBaseMotorAutoDiff() {
  return MakeAutoDiffTwin<OmniBaseMotorCost>(new OmniBaseMotorResidual{});
}

ceres::CostFunction* MakeOmniBasePlanarAutoDiff() {
  return MakeAutoDiffTwin<OmniBasePlanarCost>(new OmniBasePlanarResidual{});
}

ceres::CostFunction* MakePrismaticJointAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B, const Eigen::Vector3d& a_A, const Eigen::Vector3d& d1_A, const Eigen::Vector3d& d1_B, const Eigen::Vector3d& d2_A, const Eigen::Vector3d& d2_B) {
  return MakeAutoDiffTwin<PrismaticJointCost>(new PrismaticJointResidual{r_A, r_B, a_A, d1_A, d1_B, d2_A, d2_B});
}

ceres::CostFunction* MakeRevoluteJointAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B, const Eigen::Vector3d& a_A, const Eigen::Vector3d& a_B) {
  return MakeAutoDiffTwin<RevoluteJointCost>(new RevoluteJointResidual{r_A, r_B, a_A, a_B});
}

ceres::CostFunction* MakeSphericalJointAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B) {
  return MakeAutoDiffTwin<SphericalJointCost>(new SphericalJointResidual{r_A, r_B});
}

ceres::CostFunction* MakeUniversalJointAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B, const Eigen::Vector3d& a_A, const Eigen::Vector3d& b_B) {
  return MakeAutoDiffTwin<UniversalJointCost>(new UniversalJointResidual{r_A, r_B, a_A, b_B});
}

}  // namespace ccma
