// Linear compliance of an assembled mechanism (cli.md, "Compliance in `ccma
// statics`"): how far the end-effector yields under the loads with the
// controls held, its 6 x 6 compliance and stiffness, and its softest push
// direction, from the stiffness keys of the model (model_format.md,
// "Compliance").
//
// Method (problems/internal/compliant_equilibrium.h): the springs' energy
// 1/2 y^T H y minus the loads' work f^T y, minimised under the rigid rows
// A y = 0 on y = [ds; delta], through a null-space basis of A; analytic, the
// constraint Jacobians of the cost functions and the joints' spring
// directions, no finite differences. Linear: taken at the rigid assembly,
// without the preload's geometric stiffness, so the compliance does not
// depend on the loads and the deflection is proportional to them.
// Units: m, rad, N, N*m.
#ifndef CCMA_ANALYSES_COMPLIANCE_H_
#define CCMA_ANALYSES_COMPLIANCE_H_

#include <string>

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

class CompliantEquilibrium;

struct ComplianceReport {
  // The end-effector's displacement [m] and rotation vector [rad] under the
  // loads, world frame, controls held.
  Eigen::Matrix<double, 6, 1> deflection = Eigen::Matrix<double, 6, 1>::Zero();
  double max_body_m = 0;  // the largest displacement of a body frame's origin [m]
  // C: displacement = C wrench, for a wrench at the end-effector point (world
  // frame, moment about that point); symmetric positive semi-definite
  // [m/N, m/(N*m) = rad/N, rad/(N*m)].
  Eigen::Matrix<double, 6, 6> ee_compliance = Eigen::Matrix<double, 6, 6>::Zero();
  bool stiffness_defined = false;  // C is regular: ee_stiffness = C^-1
  Eigen::Matrix<double, 6, 6> ee_stiffness = Eigen::Matrix<double, 6, 6>::Zero();
  std::string stiffness_note;  // why ee_stiffness is not given
  // The inverse of C's block over the model's controlled components (rows and
  // columns in x, y, z, roll, pitch, yaw order, less those not controlled),
  // when that block is regular; else the note says why.
  bool controlled_stiffness_defined = false;
  Eigen::MatrixXd controlled_stiffness;
  std::string controlled_stiffness_note;
  // The largest eigenvalue of C's translational 3 x 3 block [m/N] and its
  // unit eigenvector (largest component positive; where several directions
  // are equally soft, the one of them nearest the x axis, else y, else z).
  Eigen::Vector3d most_compliant_direction = Eigen::Vector3d::UnitX();
  double most_compliant = 0;
  // Every motion that no spring resists leaves the end-effector's controlled
  // components in place; when false, the loaded mechanism is not held (C is
  // then over the motions springs resist only, and neither stiffness is
  // given). A free spin about an uncontrolled axis (a tripod's apex on three
  // ball joints) leaves it held; only ee_stiffness is then not given.
  bool held = true;
  // Non-empty when the deflection is not small against the mechanism (a
  // body moves by more than 5 % of its size, 1 + the farthest body origin
  // from the world's, or the end-effector turns by more than 0.05 rad): the
  // linear answer is then outside its range, and says so.
  std::string range_note;
};

// The end-effector's small motion over y = [ds; delta] (6 x system size):
// EndEffectorJacobian's rows, zero on the controls' yields.
Eigen::MatrixXd EndEffectorMotion(const Model& model, const State& s, int system_size);

// The report for `system` at s under the generalized loads f (system size).
ComplianceReport ComputeCompliance(const Model& model, const State& s, const CompliantEquilibrium& system,
                                   const Eigen::VectorXd& f);

// The smallest translational stiffness of the end-effector at (s, u) [N/m]:
// 1 / the largest eigenvalue of C's translational 3 x 3 block (the
// reciprocal of ComplianceReport::most_compliant; `ccma workspace`'s
// stiffness_min_N_per_m). 0 when the end-effector is not held (some motion
// no spring resists moves it); +infinity when every translation is rigid
// (C's block 0). Throws std::invalid_argument like CompliantEquilibrium.
double SmallestTranslationalStiffness(const Model& model, const State& s, const Eigen::VectorXd& u);

}  // namespace ccma

#endif  // CCMA_ANALYSES_COMPLIANCE_H_
