#include "analyses/statics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/LU>
#include <Eigen/QR>

#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"
#include "problems/internal/compliant_equilibrium.h"
#include "problems/internal/constraint_factorization.h"
#include "problems/internal/equilibrium.h"

namespace ccma {
namespace {

// The blocks of C that join joint j's bodies: the joint's, and its motor's.
std::vector<std::vector<int>> JointBlocks(const Model& model) {
  std::vector<std::vector<int>> out;
  int block = 0;
  for (const Joint& joint : model.joints) {
    out.push_back({block++});
    if (joint.actuated) out.back().push_back(block++);
  }
  return out;
}

// [M; F] (about the body's origin) that rows `blocks` put on `body`.
Eigen::Matrix<double, 6, 1> OnBody(const ConstraintSet& set, const std::vector<int>& blocks, const Eigen::MatrixXd& J_s,
                                   const Eigen::VectorXd& lambda, int body) {
  Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
  for (int b : blocks) {
    const ConstraintBlock& block = set.blocks()[static_cast<size_t>(b)];
    g += J_s.block(block.row, kPoseTangentSize * body, block.rows, kPoseTangentSize).transpose() *
         lambda.segment(block.row, block.rows);
  }
  return g;
}

// The reaction of `joint` from the generalized force [M; F] its rows put on
// a body (on_body(body)).
template <typename OnBodyFn>
JointReaction Reaction(const State& s, const Joint& joint, const OnBodyFn& on_body) {
  JointReaction r;
  r.name = joint.name;
  r.point = joint.body_a == kWorld ? joint.p_A : Eigen::Vector3d(s.R_WB(joint.body_a) * joint.p_A + s.p_WB(joint.body_a));
  // On between[1]; when that is the ground, minus what between[0] receives.
  const bool on_b = joint.body_b != kWorld;
  const int body = on_b ? joint.body_b : joint.body_a;
  const Eigen::Matrix<double, 6, 1> g = (on_b ? 1.0 : -1.0) * on_body(body);
  r.force = g.tail<3>();
  r.moment = g.head<3>() - (r.point - s.p_WB(body)).cross(r.force);
  return r;
}

// Whether the loads fix every joint's reaction and every effort: the
// multipliers may still be free within one block's own redundant rows (a
// fixed joint locks 3 rotations with 6 rows), which changes neither, so the
// test is on what every null vector of J_s^T does through each block.
bool ReactionsDetermined(const ConstraintSet& set, const Eigen::MatrixXd& J_s, const Eigen::MatrixXd& J_u) {
  Eigen::FullPivLU<Eigen::MatrixXd> lu(J_s.transpose());
  lu.setThreshold(1e-10);
  if (lu.rank() == J_s.rows()) return true;
  const Eigen::MatrixXd N = lu.kernel();  // rows x k
  const double scale = std::max(1.0, J_s.cwiseAbs().maxCoeff());
  for (const ConstraintBlock& block : set.blocks()) {
    const Eigen::MatrixXd n = N.middleRows(block.row, block.rows);
    const double through = std::max((J_s.middleRows(block.row, block.rows).transpose() * n).cwiseAbs().maxCoeff(),
                                    (J_u.middleRows(block.row, block.rows).transpose() * n).cwiseAbs().maxCoeff());
    if (through > 1e-8 * scale) return false;
  }
  return true;
}

}  // namespace

bool HasLoads(const Model& model) {
  if (model.end_effector.payload.mass > 0) return true;
  for (const Body& body : model.bodies) {
    if (body.inertia.mass > 0) return true;
  }
  for (const MobileBase& base : model.mobile_bases) {
    if (base.push_limit > 0) return true;
  }
  for (const Joint& joint : model.joints) {
    if (joint.effort.given) return true;
  }
  return false;
}

namespace {

// The rigid mechanism: reactions, determinacy and balance into `out`; the
// efforts.
Eigen::VectorXd RigidStatics(const Model& model, const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& Q,
                             StaticsReport* out) {
  const ConstraintSet set(model);
  const Equilibrium equilibrium(set, s, u);  // the rank decisions (determinacy)
  // The multipliers and efforts as EffortEvaluator and inverse dynamics get
  // them (the same factorisation and operations): at rest `ccma dynamics`
  // is `ccma statics` bit for bit.
  const ConstraintFactorization factored{set, HessianSolver{set}, s, u};
  const Eigen::MatrixXd& J_s = equilibrium.J_s();
  const Eigen::VectorXd lambda = factored.Multipliers(Q);
  out->determinate = equilibrium.rank() == J_s.rows() || ReactionsDetermined(set, J_s, equilibrium.J_u());
  out->residual = Q.size() > 0 ? (J_s.transpose() * lambda + Q).lpNorm<Eigen::Infinity>() : 0.0;
  out->balanced = out->residual <= 1e-8 * (1.0 + (Q.size() > 0 ? Q.lpNorm<Eigen::Infinity>() : 0.0));
  const std::vector<std::vector<int>> blocks = JointBlocks(model);
  for (size_t j = 0; j < model.joints.size(); ++j) {
    out->joints.push_back(Reaction(s, model.joints[j], [&](int body) { return OnBody(set, blocks[j], J_s, lambda, body); }));
  }
  return factored.Efforts(lambda);
}

// The compliant mechanism (problems/internal/compliant_equilibrium.h): a
// joint's reaction is its rigid rows' A^T lambda plus its springs' -S^T k S y.
Eigen::VectorXd CompliantStatics(const Model& model, const State& s, const Eigen::VectorXd& u,
                                 const Eigen::VectorXd& Q, StaticsReport* out) {
  const ConstraintSet set(model);
  const CompliantEquilibrium system(model, set, s, u);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(system.size());
  f.head(Q.size()) = Q;
  const Eigen::VectorXd y = system.Displacement(f);
  const Eigen::VectorXd lambda = system.Multipliers(y, f);
  const Eigen::VectorXd stretch = system.k().asDiagonal() * (system.S() * y);  // spring forces
  const Eigen::VectorXd unbalanced = system.SpringForce(y) - f - system.A().transpose() * lambda;
  out->compliant = true;
  out->determinate = system.determinate();
  out->residual = unbalanced.size() > 0 ? unbalanced.lpNorm<Eigen::Infinity>() : 0.0;
  // Balanced to the rounding of the sums the residual is made of: a very
  // soft spring (1e-6 N/m) deflects by kilometres, and a stiff one's force
  // over such positions carries rounding far above the loads.
  const Eigen::MatrixXd S_abs = system.S().cwiseAbs();
  Eigen::VectorXd terms = f.cwiseAbs() + S_abs.transpose() * (system.k().asDiagonal() * (S_abs * y.cwiseAbs()));
  if (lambda.size() > 0) terms += system.A().cwiseAbs().transpose() * lambda.cwiseAbs();
  const double scale = std::max(Q.size() > 0 ? Q.lpNorm<Eigen::Infinity>() : 0.0,
                                terms.size() > 0 ? terms.lpNorm<Eigen::Infinity>() : 0.0);
  out->balanced = out->residual <= 1e-8 * (1.0 + scale);
  for (size_t j = 0; j < model.joints.size(); ++j) {
    const CompliantJointRows& r = system.joint_rows()[j];
    out->joints.push_back(Reaction(s, model.joints[j], [&](int body) {
      const int c = kPoseTangentSize * body;
      Eigen::Matrix<double, 6, 1> g =
          system.A().block(r.a_row, c, r.a_rows, 6).transpose() * lambda.segment(r.a_row, r.a_rows) +
          system.A().block(r.motor_row, c, r.motor_rows, 6).transpose() * lambda.segment(r.motor_row, r.motor_rows);
      g -= system.S().block(r.s_row, c, r.s_rows, 6).transpose() * stretch.segment(r.s_row, r.s_rows);
      return g;
    }));
  }
  out->compliance = ComputeCompliance(model, s, system, f);
  return system.Efforts(Q);
}

// control_efforts, actuators and the limits from every control's effort.
void FillEfforts(const Model& model, const Eigen::VectorXd& u, const Eigen::VectorXd& effort, StaticsReport* report) {
  StaticsReport& out = *report;
  out.control_efforts = effort;
  for (int k = 0; k < model.num_bases(); ++k) {
    const MobileBase& base = model.mobile_bases[static_cast<size_t>(k)];
    const int first = model.base_control(k);
    for (const BaseEffort& e : KindOf(base).Efforts(u.data() + first, effort.data() + first)) {
      out.actuators.push_back({base.name, e.kind, e.value});
    }
  }
  for (const Joint& joint : model.joints) {
    if (joint.actuated) out.actuators.push_back({joint.name, "joint", effort[joint.control]});
  }
  for (int k = 0; k < model.num_bases(); ++k) {
    const MobileBase& base = model.mobile_bases[static_cast<size_t>(k)];
    if (base.push_limit <= 0) continue;
    out.limits_given = true;
    const int first = model.base_control(k);
    if (std::hypot(effort[first], effort[first + 1]) > base.push_limit * (1 + 1e-12)) out.limiting.push_back(base.name);
  }
  for (const Joint& joint : model.joints) {
    if (!joint.actuated || !joint.effort.given) continue;
    out.limits_given = true;
    const double e = effort[joint.control], slack = 1e-12 * (1 + std::abs(e));
    if (e < joint.effort.lower - slack || e > joint.effort.upper + slack) out.limiting.push_back(joint.name);
  }
  out.within_limits = out.limiting.empty();
}

}  // namespace

StaticsReport ComputeStatics(const Model& model, const State& s, const Eigen::VectorXd& u,
                             const ExternalWrench& wrench) {
  const Eigen::VectorXd Q = GeneralizedLoads(model, s, wrench);
  StaticsReport out;
  const Eigen::VectorXd effort = model.compliant() ? CompliantStatics(model, s, u, Q, &out) : RigidStatics(model, s, u, Q, &out);
  FillEfforts(model, u, effort, &out);
  return out;
}

EffortEvaluator::EffortEvaluator(const Model& model)
    : model_(model),
      set_(std::make_unique<ConstraintSet>(model)),
      symbolic_(std::make_unique<const HessianSolver>(*set_)) {}
EffortEvaluator::~EffortEvaluator() = default;

StaticsReport EffortEvaluator::At(const State& s, const Eigen::VectorXd& u, const ExternalWrench& wrench) const {
  return AtLoads(s, u, GeneralizedLoads(model_, s, wrench));
}

StaticsReport EffortEvaluator::AtLoads(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& Q) const {
  if (model_.compliant()) return Solve(s, u, Q, nullptr);
  const ConstraintFactorization factored(*set_, *symbolic_, s, u);
  return Solve(s, u, Q, &factored);
}

StaticsReport EffortEvaluator::AtLoads(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& Q,
                                       const ConstraintFactorization& factored) const {
  return Solve(s, u, Q, &factored);
}

// `factored` is read only for a rigid model (and then not null).
StaticsReport EffortEvaluator::Solve(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& Q,
                                     const ConstraintFactorization* factored) const {
  StaticsReport out;
  out.compliant = model_.compliant();
  Eigen::VectorXd effort;
  if (out.compliant) {
    const CompliantEquilibrium system(model_, *set_, s, u, CompliantEquilibrium::Factorization::kEfforts);
    effort = system.Efforts(Q, &out.residual);
  } else {
    const Eigen::VectorXd lambda = factored->Multipliers(Q);
    out.residual = Q.size() > 0 ? (factored->J_s().transpose() * lambda + Q).lpNorm<Eigen::Infinity>() : 0.0;
    effort = factored->Efforts(lambda);
  }
  FillEfforts(model_, u, effort, &out);
  return out;
}

Eigen::MatrixXd EffortEvaluator::EffortsUnder(const State& s, const Eigen::VectorXd& u,
                                              const Eigen::MatrixXd& loads) const {
  if (model_.compliant()) return SolveMany(s, u, loads, nullptr);
  const ConstraintFactorization factored(*set_, *symbolic_, s, u);
  return SolveMany(s, u, loads, &factored);
}

Eigen::MatrixXd EffortEvaluator::EffortsUnder(const State& s, const Eigen::VectorXd& u, const Eigen::MatrixXd& loads,
                                              const ConstraintFactorization& factored) const {
  return SolveMany(s, u, loads, &factored);
}

Eigen::MatrixXd EffortEvaluator::SolveMany(const State& s, const Eigen::VectorXd& u, const Eigen::MatrixXd& loads,
                                           const ConstraintFactorization* factored) const {
  Eigen::MatrixXd out(model_.num_controls(), loads.cols());
  if (model_.compliant()) {
    const CompliantEquilibrium system(model_, *set_, s, u, CompliantEquilibrium::Factorization::kEfforts);
    double residual = 0;
    for (Eigen::Index j = 0; j < loads.cols(); ++j) out.col(j) = system.Efforts(loads.col(j), &residual);
  } else {
    for (Eigen::Index j = 0; j < loads.cols(); ++j) out.col(j) = factored->Efforts(factored->Multipliers(loads.col(j)));
  }
  return out;
}

}  // namespace ccma
