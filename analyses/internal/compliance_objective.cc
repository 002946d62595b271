#include "analyses/internal/compliance_objective.h"

#include <cmath>

#include "analyses/compliance.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/loads.h"
#include "problems/internal/compliant_equilibrium.h"

namespace ccma {
namespace {

// f = [Q; 0] of the compliant system: the loads on the state, none on the yields.
Eigen::VectorXd ComplianceLoads(const Model& model, const State& s, int size) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(size);
  f.head(s.tangent_size()) = GeneralizedLoads(model, s);
  return f;
}

// The stiffness objective's vectors: nu, w = P G^T nu, mu (A^T mu = G^T nu - H w).
void StiffnessAdjoint(const CompliantEquilibrium& system, const Eigen::MatrixXd& G, const ComplianceReport& report,
                      ComplianceAdjoint* out) {
  out->weight.head<3>() = report.most_compliant_direction;
  const Eigen::VectorXd g = G.transpose() * out->weight;
  out->primal = system.Displacement(g);
  out->primal_multipliers = -system.Multipliers(out->primal, g);
}

// The deflection objective's: e, y, lambda (A^T lambda = f - H y), z, zeta.
void DeflectionAdjoint(const CompliantEquilibrium& system, const Eigen::MatrixXd& G, const Eigen::VectorXd& f,
                       const ComplianceReport& report, ComplianceAdjoint* out) {
  out->weight.head<3>() = report.deflection.head<3>() / report.deflection.head<3>().norm();
  out->primal = system.Displacement(f);
  out->primal_multipliers = -system.Multipliers(out->primal, f);
  const Eigen::VectorXd g = G.transpose() * out->weight;
  out->adjoint = system.Displacement(g);
  out->adjoint_multipliers = -system.Multipliers(out->adjoint, g);
}

// w^T A^T m for multipliers m of A's rows (none when A has no rows).
double RowWork(const CompliantEquilibrium& system, const Eigen::VectorXd& m, const Eigen::VectorXd& w) {
  return system.A().rows() == 0 ? 0.0 : m.dot(system.A() * w);
}

}  // namespace

ComplianceValue ComplianceObjectiveAt(bool stiffness, const Model& model, const State& s, const Eigen::VectorXd& u,
                                      ComplianceAdjoint* adjoint) {
  ComplianceValue out;
  if (!model.compliant()) {
    out.why = "the model has no stiffness keys (model_format.md, \"Compliance\")";
    return out;
  }
  const ConstraintSet set(model);
  const CompliantEquilibrium system(model, set, s, u);
  const Eigen::VectorXd f = ComplianceLoads(model, s, system.size());
  const ComplianceReport report = ComputeCompliance(model, s, system, f);
  if (!report.held) {
    out.why = "the end-effector is not held: some motion no spring resists moves it";
    return out;
  }
  out.value = stiffness ? report.most_compliant : report.deflection.head<3>().norm();
  out.defined = std::isfinite(out.value);
  if (!out.defined) out.why = "the compliance is not finite at the target";
  if (adjoint == nullptr || !out.defined) return out;
  *adjoint = ComplianceAdjoint();
  adjoint->stiffness = stiffness;
  const Eigen::MatrixXd G = EndEffectorMotion(model, s, system.size());
  if (stiffness) {
    StiffnessAdjoint(system, G, report, adjoint);
  } else if (out.value > 0) {  // no loads: no direction, and a zero gradient
    DeflectionAdjoint(system, G, f, report, adjoint);
  }
  return out;
}

double ComplianceLagrangian(const ComplianceAdjoint& adjoint, const Model& model, const State& s,
                            const Eigen::VectorXd& u) {
  if (adjoint.primal.size() == 0) return 0;  // a deflection of 0
  const ConstraintSet set(model);
  const CompliantEquilibrium system(model, set, s, u, CompliantEquilibrium::Factorization::kNone);
  const Eigen::MatrixXd G = EndEffectorMotion(model, s, system.size());
  const Eigen::VectorXd& y = adjoint.primal;
  const Eigen::VectorXd Gw = G.transpose() * adjoint.weight;
  if (adjoint.stiffness) {
    return 2 * Gw.dot(y) - y.dot(system.SpringForce(y)) - 2 * RowWork(system, adjoint.primal_multipliers, y);
  }
  const Eigen::VectorXd& z = adjoint.adjoint;
  const Eigen::VectorXd f = ComplianceLoads(model, s, system.size());
  return Gw.dot(y) - z.dot(system.SpringForce(y)) - RowWork(system, adjoint.primal_multipliers, z) + z.dot(f) -
         RowWork(system, adjoint.adjoint_multipliers, y);
}

}  // namespace ccma
