#include "analyses/compliance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/internal/dense_factorizations.h"
#include "ccma/internal/format.h"
#include "problems/internal/compliant_equilibrium.h"

namespace ccma {
namespace {

// Relative thresholds: a compliance this far below the largest is a rigid
// direction (rounding of the null space), and an end-effector motion no
// spring resists this small is rounding too.
constexpr double kComplianceRigid = 1e-14;
constexpr double kComplianceSingular = 1e-10;
constexpr double kComplianceUnheld = 1e-8;

// The unit eigenvector of the largest eigenvalue of C's translational block.
// Where several directions are equally soft (a symmetric mechanism), the
// one of their plane (or space) nearest the x axis (else y, else z), so
// that the answer does not depend on rounding; its largest component
// positive (the first of equals).
void MostCompliant(const Eigen::Matrix<double, 6, 6>& C, ComplianceReport* out) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C.topLeftCorner<3, 3>());
  const Eigen::Vector3d lambda = eig.eigenvalues();
  out->most_compliant = std::max(0.0, lambda[2]);
  int first = 2;  // the eigenvectors first..2 share the largest eigenvalue
  while (first > 0 && lambda[2] - lambda[first - 1] <= 1e-9 * std::abs(lambda[2])) --first;
  const Eigen::MatrixXd E = eig.eigenvectors().rightCols(3 - first);
  Eigen::Vector3d v = eig.eigenvectors().col(2);
  for (int axis = 0; axis < 3 && first < 2; ++axis) {
    const Eigen::Vector3d projected = E * (E.transpose() * Eigen::Vector3d::Unit(axis));
    if (projected.norm() > 1e-6) {
      v = projected;
      break;
    }
  }
  v.normalize();
  int largest = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(v[i]) > std::abs(v[largest]) + 1e-12) largest = i;
  }
  if (v[largest] < 0) v = -v;
  out->most_compliant_direction = v;
}

// C^-1 when C (a square block of the compliance) is regular: no direction
// rigid (a diagonal entry negligible against the largest) and its
// correlation matrix (unit-free) regular. Where it is not, *note says why:
// the mechanism holds some combination of directions rigidly (`moved` <
// C's size: decided on the geometry), or the springs' stiffness spans so
// many orders of magnitude that C cannot be inverted to rounding (every
// direction yields, some 1e10 times less).
bool InvertCompliance(const Eigen::MatrixXd& C, int moved, Eigen::MatrixXd* K, std::string* note) {
  const Eigen::Index n = C.rows();
  if (n == 0) {
    *note = "the model controls no component of the end-effector";
    return false;
  }
  const Eigen::VectorXd d = C.diagonal();
  const double largest = d.maxCoeff();
  if (moved < n) {
    *note = "the compliance is singular: the mechanism holds some combination of directions rigidly "
            "(compliance 0 along it)";
    return false;
  }
  const char* const kIllConditioned =
      "the compliance is too ill-conditioned to invert: every direction yields, but the softest more than 1e10 "
      "times as much as the stiffest (the springs' stiffness values span too many orders of magnitude)";
  *note = kIllConditioned;
  if (!(largest > 0) || d.minCoeff() <= kComplianceRigid * largest) return false;
  const Eigen::VectorXd scale = d.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd correlation = scale.asDiagonal() * C * scale.asDiagonal();
  const SymmetricEigenSolver eig(correlation);
  if (eig.eigenvalues()[0] <= kComplianceSingular * eig.eigenvalues()[n - 1]) return false;
  const Eigen::MatrixXd inverse = C.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
  *K = 0.5 * (inverse + inverse.transpose());
  if (!K->allFinite()) return false;
  note->clear();
  return true;
}

// ee_stiffness and controlled_stiffness from C. The whole end-effector's
// stiffness needs every motion no spring resists to leave all six
// components in place (`all_held`); the controlled block's, the controlled
// ones (out->held).
void StiffnessFromCompliance(const Model& model, const CompliantEquilibrium& system, const Eigen::MatrixXd& G,
                             bool all_held, ComplianceReport* out) {
  const char* const kNotHeld = "the mechanism is not held: some motion no spring resists moves the end-effector";
  if (!out->held) {
    out->stiffness_note = out->controlled_stiffness_note = kNotHeld;
    return;
  }
  const Eigen::MatrixXd G_c = ControlledRows(model, G);
  const Eigen::MatrixXd C_c = ControlledRows(model, ControlledRows(model, out->ee_compliance).transpose());
  out->controlled_stiffness_defined =
      InvertCompliance(C_c, system.MovedDirections(G_c), &out->controlled_stiffness, &out->controlled_stiffness_note);
  if (!all_held) {
    out->stiffness_note = "the end-effector body moves freely along components the model does not control (no spring "
                          "resists it there): see controlled_stiffness";
    return;
  }
  Eigen::MatrixXd K;
  out->stiffness_defined = InvertCompliance(out->ee_compliance, system.MovedDirections(G), &K, &out->stiffness_note);
  if (out->stiffness_defined) out->ee_stiffness = K;
}

}  // namespace

Eigen::MatrixXd EndEffectorMotion(const Model& model, const State& s, int system_size) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(6, system_size);
  G.leftCols(model.state_size()) = EndEffectorJacobian(model, s);
  return G;
}

ComplianceReport ComputeCompliance(const Model& model, const State& s, const CompliantEquilibrium& system,
                                   const Eigen::VectorXd& f) {
  ComplianceReport out;
  const Eigen::MatrixXd G = EndEffectorMotion(model, s, system.size());
  const Eigen::VectorXd y = system.Displacement(f);
  out.deflection = G * y;
  for (int b = 0; b < model.num_bodies(); ++b) out.max_body_m = std::max(out.max_body_m, y.segment<3>(6 * b + 3).norm());
  out.ee_compliance = system.Compliance(G);
  out.held = system.UnheldMotion(ControlledRows(model, G)) <= kComplianceUnheld;
  MostCompliant(out.ee_compliance, &out);
  StiffnessFromCompliance(model, system, G, system.UnheldMotion(G) <= kComplianceUnheld, &out);
  double size = 0;
  for (int b = 0; b < model.num_bodies(); ++b) size = std::max(size, s.p_WB(b).norm());
  const double turn = out.deflection.tail<3>().norm();
  if (out.held && (out.max_body_m > 0.05 * (1 + size) || turn > 0.05)) {
    out.range_note = "the linear deflection (" + FormatG(out.max_body_m, 3) + " m at the farthest body, " +
                     FormatG(turn, 3) + " rad at the end-effector) is not small against the mechanism (" +
                     FormatG(1 + size, 3) + " m): linear statics holds for small deflections; ccma simulate --loaded "
                     "gives the nonlinear equilibrium";
  }
  return out;
}

double SmallestTranslationalStiffness(const Model& model, const State& s, const Eigen::VectorXd& u) {
  const ConstraintSet set(model);
  const CompliantEquilibrium system(model, set, s, u);
  const ComplianceReport report = ComputeCompliance(model, s, system, Eigen::VectorXd::Zero(system.size()));
  if (!report.held) return 0;
  if (!(report.most_compliant > 0)) return std::numeric_limits<double>::infinity();
  return 1 / report.most_compliant;
}

}  // namespace ccma
