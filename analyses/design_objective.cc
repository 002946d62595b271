#include "analyses/design_objective.h"

#include <cmath>
#include <functional>
#include <vector>


#include "analyses/internal/compliance_objective.h"
#include "analyses/payload.h"
#include "ccma/internal/dense_factorizations.h"
#include "ccma/loads.h"
#include "problems/internal/end_effector_error.h"
#include "problems/internal/equilibrium.h"

namespace ccma {
namespace {

// Central-difference step along a tangent, relative to its largest entry.
constexpr double kTangentStep = 1e-5;

// The largest horizontal push of any base at (s, u) under all the loads,
// and w with w . e = that push (the unit push direction on the base's x, y).
struct PushPeak {
  ObjectiveAtTarget at;
  Eigen::VectorXd w;
};

PushPeak PeakPush(const Model& model, const State& s, const Eigen::VectorXd& u) {
  PushPeak out;
  if (model.num_bases() == 0) {
    out.at.why = "the model has no mobile bases";
    return out;
  }
  const ConstraintSet set(model);
  const Equilibrium eq(set, s, u);
  const Eigen::VectorXd e = eq.Efforts(eq.Multipliers(GeneralizedLoads(model, s)));
  int worst = 0;
  for (int k = 1; k < model.num_bases(); ++k) {
    if (e.segment<2>(model.base_control(k)).norm() > e.segment<2>(model.base_control(worst)).norm()) worst = k;
  }
  const Eigen::Vector2d v = e.segment<2>(model.base_control(worst));
  out.at.value = v.norm();
  out.at.limiting = model.mobile_bases[static_cast<size_t>(worst)].name;
  out.w = Eigen::VectorXd::Zero(e.size());
  if (v.norm() > 0) out.w.segment<2>(model.base_control(worst)) = v / v.norm();
  out.at.defined = true;
  return out;
}

// One weighted effort w . e of the Lagrangian (equilibrium.h): the loads
// (a variant of the design's model) and the multipliers at the target.
struct EffortTerm {
  std::function<Model(const Model&)> loads;
  Eigen::VectorXd w;
  Equilibrium::Adjoint adjoint;
};

// The terms whose sum's derivative is the objective's (payload, peak_push).
bool EffortTerms(DesignObjective objective, const Model& at_p, const State& s, const Eigen::VectorXd& u,
                 std::vector<EffortTerm>* terms, std::string* why) {
  const ConstraintSet set(at_p);
  const Equilibrium eq(set, s, u);
  if (objective == DesignObjective::kPayload) {
    const PayloadCapacity c = ComputePayloadCapacity(at_p, s, u);
    if (!c.defined || c.unbounded) {
      *why = c.defined ? "no limited effort grows with the payload" : c.why;
      return false;
    }
    terms->push_back({WithoutPayload, c.weight_own, {}});
    terms->push_back({PayloadPerKilogram, c.weight_kg, {}});
  } else {
    const PushPeak peak = PeakPush(at_p, s, u);
    if (!peak.at.defined) {
      *why = peak.at.why;
      return false;
    }
    terms->push_back({[](const Model& m) { return m; }, peak.w, {}});
  }
  for (EffortTerm& t : *terms) {
    t.adjoint = eq.AdjointOf(t.w, GeneralizedLoads(t.loads(at_p), s));
    // A compliant mechanism's efforts are the rigid ones wherever those are
    // unique; elsewhere the springs share the loads, which this adjoint
    // (of the rigid statics) does not follow.
    if (at_p.compliant() && !t.adjoint.unique) {
      *why = "the efforts of this statically indeterminate mechanism come from its springs (stiffness keys), "
             "whose sharing of the loads the gradient does not follow";
      return false;
    }
  }
  return true;
}

// ds/dp and du/dp (total, controls following the design) at a target.
bool TargetTangent(const Model& model, const DesignParameters& params, const Eigen::VectorXd& p, const State& s,
                   const Eigen::VectorXd& u, Eigen::MatrixXd* ds, Eigen::MatrixXd* du, std::string* why) {
  ParameterSensitivity sens;
  const Model at_p = ApplyParameters(model, params, p);
  const Eigen::MatrixXd ds_du = StateControlSensitivity(at_p, s, u);
  if (!ComputeParameterSensitivity(model, params, p, s, u, &sens) || ds_du.rows() != s.tangent_size()) {
    *why = "dG/ds is singular at the target";
    return false;
  }
  const EndEffectorPose pose = ComputeEndEffectorPose(at_p, s);
  Eigen::VectorXd e;
  Eigen::MatrixXd de_ds;
  EndEffectorError(at_p).Evaluate(s, {pose.position, pose.rpy}, &e, &de_ds);
  MinimumNormSolver cod(de_ds * ds_du);
  *du = -cod.solveMatrix(de_ds * sens.ds_dp);
  *ds = sens.ds_dp + ds_du * *du;
  return ds->allFinite() && du->allFinite();
}

// (f(+h) - f(-h)) / 2h along tangent column k: state, controls and p_k.
double AlongTangent(const Model& model, const DesignParameters& params, const Eigen::VectorXd& p, const State& s,
                    const Eigen::VectorXd& u, const Eigen::VectorXd& ds, const Eigen::VectorXd& du, int k,
                    const std::function<double(const Model&, const State&, const Eigen::VectorXd&)>& f) {
  const double h = kTangentStep / std::max({1.0, ds.lpNorm<Eigen::Infinity>(), du.lpNorm<Eigen::Infinity>()});
  double value[2];
  for (int side = 0; side < 2; ++side) {
    const double t = side == 0 ? h : -h;
    State st = s;
    st.Plus(t * ds);
    Eigen::VectorXd pt = p;
    pt[k] += t;
    value[side] = f(ApplyParameters(model, params, pt), st, u + t * du);
  }
  return (value[0] - value[1]) / (2 * h);
}

double EndEffectorStd(const Model& model, const State& s, const Eigen::VectorXd& u, const BasePoseNoise& noise) {
  return std::sqrt(EndEffectorCovariance(model, s, u, noise).topLeftCorner<3, 3>().trace());
}

// stiffness or deflection at (s, u) (analyses/internal/compliance_objective.h).
ObjectiveAtTarget ComplianceObjective(DesignObjective objective, const Model& model, const State& s,
                                      const Eigen::VectorXd& u, ComplianceAdjoint* adjoint = nullptr) {
  const ComplianceValue v = ComplianceObjectiveAt(objective == DesignObjective::kStiffness, model, s, u, adjoint);
  ObjectiveAtTarget out;
  out.defined = v.defined;
  out.value = v.value;
  out.why = v.why;
  return out;
}

}  // namespace

bool ParseDesignObjective(const std::string& name, DesignObjective* out) {
  for (DesignObjective o : {DesignObjective::kReach, DesignObjective::kPayload, DesignObjective::kPeakPush,
                            DesignObjective::kEndEffectorStd, DesignObjective::kStiffness,
                            DesignObjective::kDeflection}) {
    if (name == DesignObjectiveName(o)) {
      *out = o;
      return true;
    }
  }
  return false;
}

const char* DesignObjectiveName(DesignObjective objective) {
  switch (objective) {
    case DesignObjective::kPayload: return "payload";
    case DesignObjective::kPeakPush: return "peak_push";
    case DesignObjective::kEndEffectorStd: return "ee_std";
    case DesignObjective::kStiffness: return "stiffness";
    case DesignObjective::kDeflection: return "deflection";
    default: return "reach";
  }
}

const char* DesignObjectiveUnit(DesignObjective objective) {
  switch (objective) {
    case DesignObjective::kPayload: return "kg";
    case DesignObjective::kPeakPush: return "N";
    case DesignObjective::kEndEffectorStd: return "m";
    case DesignObjective::kStiffness: return "m/N";
    case DesignObjective::kDeflection: return "m";
    default: return "";
  }
}

ObjectiveAtTarget EvaluateObjective(DesignObjective objective, const Model& model, const State& s,
                                    const Eigen::VectorXd& u, const BasePoseNoise& noise) {
  ObjectiveAtTarget out;
  if (objective == DesignObjective::kPayload) {
    const PayloadCapacity c = ComputePayloadCapacity(model, s, u);
    out.defined = c.defined && !c.unbounded;
    out.value = c.mass;
    out.limiting = c.limiting;
    out.why = c.defined ? (c.unbounded ? "no limited effort grows with the payload" : "") : c.why;
  } else if (objective == DesignObjective::kPeakPush) {
    out = PeakPush(model, s, u).at;
  } else if (objective == DesignObjective::kEndEffectorStd) {
    out.value = EndEffectorStd(model, s, u, noise);
    out.defined = std::isfinite(out.value);
    if (!out.defined) out.why = "dG/ds is singular at the target";
  } else if (objective == DesignObjective::kStiffness || objective == DesignObjective::kDeflection) {
    out = ComplianceObjective(objective, model, s, u);
  } else {
    out.why = "reach has no value to improve";
  }
  return out;
}

bool ObjectiveGradient(DesignObjective objective, const Model& model, const DesignParameters& params,
                       const Eigen::VectorXd& p, const State& s, const Eigen::VectorXd& u,
                       const BasePoseNoise& noise, Eigen::VectorXd* gradient, std::string* why) {
  const Model at_p = ApplyParameters(model, params, p);
  Eigen::MatrixXd ds, du;
  if (objective == DesignObjective::kReach || !TargetTangent(model, params, p, s, u, &ds, &du, why)) {
    if (objective == DesignObjective::kReach) *why = "reach has no gradient";
    return false;
  }
  std::function<double(const Model&, const State&, const Eigen::VectorXd&)> f;
  std::vector<EffortTerm> terms;
  ComplianceAdjoint adjoint;  // stiffness, deflection
  if (objective == DesignObjective::kEndEffectorStd) {
    f = [&noise](const Model& m, const State& st, const Eigen::VectorXd& ut) { return EndEffectorStd(m, st, ut, noise); };
  } else if (objective == DesignObjective::kStiffness || objective == DesignObjective::kDeflection) {
    const ObjectiveAtTarget here = ComplianceObjective(objective, at_p, s, u, &adjoint);
    if (!here.defined) {
      *why = here.why;
      return false;
    }
    f = [&adjoint](const Model& m, const State& st, const Eigen::VectorXd& ut) {
      return ComplianceLagrangian(adjoint, m, st, ut);
    };
  } else {
    if (!EffortTerms(objective, at_p, s, u, &terms, why)) return false;
    f = [&terms](const Model& m, const State& st, const Eigen::VectorXd& ut) {
      const ConstraintSet set(m);
      double L = 0;
      for (const EffortTerm& t : terms) L += EffortLagrangian(set, t.loads(m), st, ut, t.w, t.adjoint);
      return L;
    };
  }
  gradient->resize(params.size());
  for (int k = 0; k < params.size(); ++k) (*gradient)[k] = AlongTangent(model, params, p, s, u, ds.col(k), du.col(k), k, f);
  if (!gradient->allFinite()) *why = "the gradient is not finite at the target";
  return gradient->allFinite();
}

}  // namespace ccma
