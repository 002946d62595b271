#include "analyses/design.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>
#include <yaml-cpp/yaml.h>

#include "ccma/internal/constraint_set.h"
#include "formats/model_loader.h"
#include "problems/internal/end_effector_error.h"
#include "problems/internal/sensitivity.h"

namespace ccma {
namespace {

// Pivot ratio below which dG/ds counts as singular (as in sensitivity.cc).
constexpr double kSingularRcond = 1e-12;
// Step of the central difference of G in p [m]. G is quadratic in p, so the
// difference is exact for any h; 1e-3 keeps rounding (~eps |G| / h) tiny.
constexpr double kGradientStep = 1e-3;
// Step of the central difference of sigma_min in p [m] (margin phase).
constexpr double kSigmaStep = 1e-4;
// Distinct home points: two joints closer than this cannot define a length.
constexpr double kMinAnchorDistance = 1e-9;
// Joint-limit violation still counted as respecting the limits [rad or m].
constexpr double kLimitSlack = 1e-9;

bool IsVaried(const DesignParameters& params, int joint) {
  for (const DesignParameter& q : params.list) {
    if (q.joint == joint) return true;
  }
  return false;
}

bool IsAnchor(const DesignParameters& params, int joint) {
  for (const DesignParameter& q : params.list) {
    if (q.kind == DesignParameterKind::kLinkLength && q.anchor == joint) return true;
  }
  return false;
}

bool SharesBody(const Joint& a, const Joint& b) {
  for (int x : {a.body_a, a.body_b}) {
    if (x == kWorld) continue;
    if (x == b.body_a || x == b.body_b) return true;
  }
  return false;
}

// Body-frame copy of a world home point on `body` (the world: itself).
Eigen::Vector3d InBody(const Model& model, int body, const Eigen::Vector3d& p_W) {
  if (body == kWorld) return p_W;
  const Body& b = model.bodies[body];
  return b.R_WB_home.transpose() * (p_W - b.p_WB_home);
}

}  // namespace

bool AddJointCoordinates(const Model& model, const std::string& item, DesignParameters* params, std::string* why) {
  const std::size_t dot = item.rfind('.');
  const std::string name = dot == std::string::npos ? item : item.substr(0, dot);
  const std::string what = dot == std::string::npos ? "" : item.substr(dot + 1);
  const int joint = model.FindJoint(name);
  if (joint < 0) {
    *why = "'" + item + "': no joint named '" + name + "' (expected JOINT.x, .y, .z or .point)";
    return false;
  }
  std::vector<int> axes;
  if (what == "x") axes = {0};
  else if (what == "y") axes = {1};
  else if (what == "z") axes = {2};
  else if (what == "point") axes = {0, 1, 2};
  else {
    *why = "'" + item + "': expected JOINT.x, JOINT.y, JOINT.z or JOINT.point";
    return false;
  }
  for (int axis : axes) {
    for (const DesignParameter& q : params->list) {
      const bool same = q.joint == joint && (q.kind == DesignParameterKind::kLinkLength || q.axis == axis);
      if (same || q.anchor == joint) {
        *why = "'" + item + "': the point of joint '" + name + "' is already varied or anchors a length";
        return false;
      }
    }
    DesignParameter q;
    q.kind = DesignParameterKind::kJointCoordinate;
    q.joint = joint;
    q.axis = axis;
    q.label = name + "." + "xyz"[axis];
    params->list.push_back(q);
  }
  return true;
}

bool AddLinkLength(const Model& model, const std::string& item, DesignParameters* params, std::string* why) {
  const std::size_t colon = item.find(':');
  if (colon == std::string::npos) {
    *why = "'" + item + "': expected ANCHOR_JOINT:MOVED_JOINT";
    return false;
  }
  const std::string a_name = item.substr(0, colon), b_name = item.substr(colon + 1);
  const int a = model.FindJoint(a_name), b = model.FindJoint(b_name);
  if (a < 0 || b < 0) {
    *why = "'" + item + "': no joint named '" + (a < 0 ? a_name : b_name) + "'";
    return false;
  }
  if (a == b || !SharesBody(model.joints[a], model.joints[b])) {
    *why = "'" + item + "': the two joints must differ and share a body (the link)";
    return false;
  }
  if (IsVaried(*params, b) || IsVaried(*params, a) || IsAnchor(*params, b)) {
    *why = "'" + item + "': a joint of it is already varied or anchors another length";
    return false;
  }
  const Eigen::Vector3d d = JointPointWorld(model, b) - JointPointWorld(model, a);
  if (!(d.norm() > kMinAnchorDistance)) {
    *why = "'" + item + "': the two joints are at the same point (no length)";
    return false;
  }
  DesignParameter q;
  q.kind = DesignParameterKind::kLinkLength;
  q.joint = b;
  q.anchor = a;
  q.direction_W = d.normalized();
  q.label = "length:" + a_name + ":" + b_name;
  params->list.push_back(q);
  return true;
}

Eigen::Vector3d JointPointWorld(const Model& model, int joint) {
  const Joint& j = model.joints[joint];
  if (j.body_a == kWorld) return j.p_A;
  const Body& a = model.bodies[j.body_a];
  return a.R_WB_home * j.p_A + a.p_WB_home;
}

Eigen::VectorXd ParameterValues(const Model& model, const DesignParameters& params) {
  Eigen::VectorXd p(params.size());
  for (int k = 0; k < params.size(); ++k) {
    const DesignParameter& q = params.list[k];
    const Eigen::Vector3d P = JointPointWorld(model, q.joint);
    p[k] = q.kind == DesignParameterKind::kJointCoordinate ? P[q.axis]
                                                           : (P - JointPointWorld(model, q.anchor)).norm();
  }
  return p;
}

Model ApplyParameters(const Model& model, const DesignParameters& params, const Eigen::VectorXd& p) {
  if (p.size() != params.size()) throw std::invalid_argument("ApplyParameters: p has the wrong size");
  Model out = model;
  // New world points of the moved joints (anchors never move, so the order
  // of the parameters does not matter).
  std::vector<std::pair<int, Eigen::Vector3d>> moved;
  auto point = [&](int joint) -> Eigen::Vector3d& {
    for (auto& m : moved) {
      if (m.first == joint) return m.second;
    }
    moved.emplace_back(joint, JointPointWorld(model, joint));
    return moved.back().second;
  };
  for (int k = 0; k < params.size(); ++k) {
    const DesignParameter& q = params.list[k];
    if (q.kind == DesignParameterKind::kJointCoordinate) {
      point(q.joint)[q.axis] = p[k];
    } else {
      point(q.joint) = JointPointWorld(model, q.anchor) + p[k] * q.direction_W;
    }
  }
  for (const auto& [joint, P_W] : moved) {
    Joint& j = out.joints[joint];
    j.p_A = InBody(model, j.body_a, P_W);
    j.p_B = InBody(model, j.body_b, P_W);
  }
  return out;
}

Eigen::MatrixXd EnergyGradientParameterJacobian(const Model& model, const DesignParameters& params,
                                                const Eigen::VectorXd& p, const State& s, const Eigen::VectorXd& u) {
  const int n = s.tangent_size();
  Eigen::MatrixXd dG_dp(n, params.size());
  EnergyDerivatives plus, minus;
  for (int k = 0; k < params.size(); ++k) {
    Eigen::VectorXd pk = p;
    pk[k] = p[k] + kGradientStep;
    const Model model_plus = ApplyParameters(model, params, pk);
    pk[k] = p[k] - kGradientStep;
    const Model model_minus = ApplyParameters(model, params, pk);
    ConstraintSet(model_plus).EvaluateDerivatives(s, u, &plus);
    ConstraintSet(model_minus).EvaluateDerivatives(s, u, &minus);
    dG_dp.col(k) = (plus.G - minus.G) / (2 * kGradientStep);
  }
  return dG_dp;
}

bool SolveStateParameterSensitivity(const ConstraintSet& constraints, const State& s, const Eigen::VectorXd& u,
                                    const Eigen::MatrixXd& dG_dp, Eigen::MatrixXd* ds_dp, double* rcond) {
  EnergyDerivatives d;
  constraints.EvaluateDerivatives(s, u, &d);
  HessianSolver solver(constraints);
  *rcond = solver.Factorize(d.H) ? solver.pivot_ratio() : 0;
  if (!(*rcond > kSingularRcond)) return false;
  *ds_dp = -solver.Solve(dG_dp);
  return ds_dp->allFinite();
}

bool ComputeParameterSensitivity(const Model& model, const DesignParameters& params, const Eigen::VectorXd& p,
                                 const State& s, const Eigen::VectorXd& u, ParameterSensitivity* out) {
  const Model at_p = ApplyParameters(model, params, p);
  const ConstraintSet constraints(at_p);
  out->dG_dp = EnergyGradientParameterJacobian(model, params, p, s, u);
  out->singular = !SolveStateParameterSensitivity(constraints, s, u, out->dG_dp, &out->ds_dp, &out->rcond);
  if (out->singular) return false;
  // The end-effector point is on its body and does not depend on p.
  out->dX_dp = EndEffectorJacobian(at_p, s) * out->ds_dp;
  return true;
}

std::string PatchModelText(const std::string& text, const Model& original, const Model& designed,
                           const DesignParameters& params) {
  struct Edit {
    std::size_t begin, end;
    std::string value;
  };
  std::vector<Edit> edits;
  const YAML::Node root = YAML::Load(text);
  const YAML::Node joints = root["joints"];
  for (int j = 0; j < static_cast<int>(designed.joints.size()); ++j) {
    if (!IsVaried(params, j)) continue;
    const std::string where = "joint '" + designed.joints[j].name + "' (line " +
                              std::to_string(designed.joints[j].line) + ")";
    if (!joints.IsSequence() || j >= static_cast<int>(joints.size())) {
      throw std::runtime_error("cannot find " + where + " in the model text");
    }
    const YAML::Node point = joints[j]["point"];
    if (!point.IsSequence() || point.size() != 3) {
      throw std::runtime_error("cannot patch the point of " + where + ": not a list of 3 numbers");
    }
    const Eigen::Vector3d old_W = JointPointWorld(original, j), new_W = JointPointWorld(designed, j);
    for (int i = 0; i < 3; ++i) {
      if (old_W[i] == new_W[i]) continue;  // only what moved
      const std::size_t begin = static_cast<std::size_t>(point[i].Mark().pos);
      std::size_t end = begin;
      while (end < text.size() && std::string(",]} \t\r\n#").find(text[end]) == std::string::npos) ++end;
      if (begin >= text.size() || end == begin) {
        throw std::runtime_error("cannot patch the point of " + where + ": no number at its mark");
      }
      char buffer[40];
      std::snprintf(buffer, sizeof buffer, "%.12g", new_W[i]);
      edits.push_back({begin, end, buffer});
    }
  }
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.begin > b.begin; });
  std::string out = text;
  for (const Edit& e : edits) out.replace(e.begin, e.end - e.begin, e.value);
  // The written model must be the designed one.
  const Model reloaded = LoadModelFromString(out, original.source.empty() ? "designed model" : original.source);
  for (int j = 0; j < static_cast<int>(designed.joints.size()); ++j) {
    const double moved = (JointPointWorld(reloaded, j) - JointPointWorld(designed, j)).norm();
    if (!(moved < 1e-9)) {
      throw std::runtime_error("the patched model text does not reproduce joint '" + designed.joints[j].name +
                               "' (off by " + std::to_string(moved) + " m)");
    }
  }
  return out;
}

// ---- The design loop ----------------------------------------------------

bool DesignOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& m) {
    if (why != nullptr) *why = m;
    return false;
  };
  if (!control.IsValid(why)) return false;
  if (!(target_tolerance >= 1e-12 && target_tolerance <= 1)) return fail("target_tolerance must be in [1e-12, 1]");
  if (!(min_singular_value >= 0 && min_singular_value <= 100)) return fail("min_singular_value must be in [0, 100]");
  if (!(max_change > 0 && max_change <= 100)) return fail("max_change must be in (0, 100]");
  if (!(min_length > 0 && min_length <= 100)) return fail("min_length must be in (0, 100]");
  if (!(max_iterations >= 1 && max_iterations <= 1000)) return fail("max_iterations must be in [1, 1000]");
  return true;
}

namespace {

// One target solved on one design, with what the p step needs.
struct SolvedTarget {
  DesignTargetResult result;
  Eigen::VectorXd e;      // end-effector error (controlled components)
  Eigen::MatrixXd de_du;  // over the effective controls
  Eigen::MatrixXd de_ds;
  State s;
  Eigen::VectorXd u;
  bool usable = false;    // e, de_du valid
};

SolvedTarget SolveTarget(const Model& model, const PoseTarget& target, const DesignOptions& options,
                         bool linearize) {
  SolvedTarget out;
  ControlProblem problem(model, options.control);
  const ForwardResult home = problem.SetControls(model.home_controls());
  out.result.controls = model.home_controls();
  if (!home.assembled) return out;  // this design does not even assemble at home
  ControlResult r;
  try {
    r = problem.MoveTo(target);
  } catch (const std::invalid_argument&) {
    return out;
  }
  out.s = problem.forward().state();
  out.u = problem.controls();
  out.result.controls = out.u;
  out.result.error = r.error;
  out.result.min_singular_value = std::isfinite(r.min_singular_value_dX_du) ? r.min_singular_value_dX_du : 0;
  out.result.within_limits = r.max_limit_violation <= kLimitSlack;
  out.result.reached = r.assembled && std::isfinite(r.error) && r.error <= options.target_tolerance &&
                       out.result.within_limits;
  const EndEffectorError error(model);
  error.Evaluate(out.s, target, &out.e, linearize ? &out.de_ds : nullptr);
  out.usable = out.e.allFinite();
  if (linearize && out.usable) {
    const Eigen::MatrixXd ds_du = problem.StateSensitivity();
    out.de_du = out.de_ds * ds_du;
    out.usable = out.de_du.allFinite();
  }
  return out;
}

double SumSquaredError(const std::vector<SolvedTarget>& solved) {
  double f = 0;
  for (const SolvedTarget& t : solved) f += t.usable ? t.e.squaredNorm() : std::numeric_limits<double>::infinity();
  return f;
}

bool AllReached(const std::vector<SolvedTarget>& solved) {
  for (const SolvedTarget& t : solved) {
    if (!t.result.reached) return false;
  }
  return true;
}

double MinSigma(const std::vector<SolvedTarget>& solved) {
  double s = std::numeric_limits<double>::infinity();
  for (const SolvedTarget& t : solved) s = std::min(s, t.result.min_singular_value);
  return s;
}

// p clipped to the bounds: |p - p0| <= max_change, lengths >= min_length.
Eigen::VectorXd Clip(const DesignParameters& params, const Eigen::VectorXd& p0, const Eigen::VectorXd& p,
                     const DesignOptions& options) {
  Eigen::VectorXd q = p;
  for (int k = 0; k < q.size(); ++k) {
    q[k] = std::clamp(q[k], p0[k] - options.max_change, p0[k] + options.max_change);
    if (params.list[k].kind == DesignParameterKind::kLinkLength) q[k] = std::max(q[k], options.min_length);
  }
  return q;
}

std::vector<SolvedTarget> SolveAll(const Model& model, const DesignParameters& params, const Eigen::VectorXd& p,
                                   const std::vector<PoseTarget>& targets, const DesignOptions& options,
                                   bool linearize) {
  const Model at_p = ApplyParameters(model, params, p);
  std::vector<SolvedTarget> out;
  out.reserve(targets.size());
  for (const PoseTarget& t : targets) out.push_back(SolveTarget(at_p, t, options, linearize));
  return out;
}

std::vector<DesignTargetResult> Results(const std::vector<SolvedTarget>& solved) {
  std::vector<DesignTargetResult> r;
  for (const SolvedTarget& t : solved) r.push_back(t.result);
  return r;
}

}  // namespace

std::vector<DesignTargetResult> EvaluateTargets(const Model& model, const std::vector<PoseTarget>& targets,
                                                const DesignOptions& options) {
  std::vector<DesignTargetResult> r;
  for (const PoseTarget& t : targets) r.push_back(SolveTarget(model, t, options, false).result);
  return r;
}

DesignResult Design(const Model& model, const DesignParameters& params, const std::vector<PoseTarget>& targets,
                    const DesignOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("design options: " + why);
  if (params.size() == 0) throw std::invalid_argument("design: no parameters to vary");
  if (targets.empty()) throw std::invalid_argument("design: no targets");
  DesignResult result;
  result.p0 = ParameterValues(model, params);
  Eigen::VectorXd p = result.p0;
  std::vector<SolvedTarget> solved = SolveAll(model, params, p, targets, options, true);
  result.initial = Results(solved);
  double f = SumSquaredError(solved);
  const int P = params.size();
  double mu = -1;  // LM damping, set from the first linearisation

  // Phase 1: reach every target (LM over the stacked errors).
  int it = 0;
  for (; it < options.max_iterations && !AllReached(solved); ++it) {
    int rows = 0, cols = P;
    for (const SolvedTarget& t : solved) {
      if (!t.usable) {
        result.message = "a target could not be solved on the current design";
        result.p = p;
        result.iterations = it;
        result.final = Results(solved);
        return result;
      }
      rows += static_cast<int>(t.e.size());
      cols += static_cast<int>(t.de_du.cols());
    }
    // J = [blockdiag(de_t/du_t) | de_t/dp], r = e.
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(rows, cols);
    Eigen::VectorXd r(rows);
    const Model at_p = ApplyParameters(model, params, p);
    int row = 0, col = 0;
    bool ok = true;
    for (SolvedTarget& t : solved) {
      ParameterSensitivity sens;
      if (!ComputeParameterSensitivity(model, params, p, t.s, t.u, &sens)) {
        ok = false;
        break;
      }
      const int m = static_cast<int>(t.e.size()), k = static_cast<int>(t.de_du.cols());
      J.block(row, col, m, k) = t.de_du;
      J.block(row, cols - P, m, P) = t.de_ds * sens.ds_dp;
      r.segment(row, m) = t.e;
      row += m;
      col += k;
    }
    if (!ok) {
      result.message = "dG/ds is singular at a target on the current design";
      break;
    }
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::VectorXd Jtr = J.transpose() * r;
    if (mu < 0) mu = 1e-3 * std::max(JtJ.diagonal().maxCoeff(), 1e-12);
    bool accepted = false;
    while (mu < 1e12) {
      Eigen::MatrixXd A = JtJ;
      A.diagonal().array() += mu;
      const Eigen::VectorXd step = A.ldlt().solve(-Jtr);
      const Eigen::VectorXd p_trial = Clip(params, result.p0, p + step.tail(P), options);
      if ((p_trial - p).norm() < 1e-14) {
        mu *= 10;
        continue;
      }
      std::vector<SolvedTarget> trial = SolveAll(model, params, p_trial, targets, options, true);
      const double f_trial = SumSquaredError(trial);
      if (f_trial < f) {
        p = p_trial;
        solved = std::move(trial);
        f = f_trial;
        mu = std::max(mu / 3, 1e-12);
        accepted = true;
        break;
      }
      mu *= 10;
    }
    if (!accepted) {
      result.message = "no design step reduces the target errors further (bounds or a local minimum)";
      break;
    }
  }

  // Phase 2: margin. Raise the smallest sigma_min while every target stays
  // reached (sigma of the worst target, its gradient in p by re-solved
  // central differences).
  for (; it < options.max_iterations && AllReached(solved) && MinSigma(solved) < options.min_singular_value;
       ++it) {
    int worst = 0;
    for (int t = 1; t < static_cast<int>(solved.size()); ++t) {
      if (solved[t].result.min_singular_value < solved[worst].result.min_singular_value) worst = t;
    }
    Eigen::VectorXd g(P);
    for (int k = 0; k < P; ++k) {
      Eigen::VectorXd pk = p;
      pk[k] += kSigmaStep;
      const Model plus = ApplyParameters(model, params, pk);
      pk[k] -= 2 * kSigmaStep;
      const Model minus = ApplyParameters(model, params, pk);
      g[k] = (SolveTarget(plus, targets[worst], options, false).result.min_singular_value -
              SolveTarget(minus, targets[worst], options, false).result.min_singular_value) /
             (2 * kSigmaStep);
    }
    if (!(g.squaredNorm() > 0) || !g.allFinite()) {
      result.message = "the margin cannot be raised (sigma_min does not change with the parameters)";
      break;
    }
    const double sigma = MinSigma(solved);
    // Newton step on sigma toward 1.5 times the threshold, at most 0.05 m.
    Eigen::VectorXd step = (1.5 * options.min_singular_value - sigma) * g / g.squaredNorm();
    if (step.norm() > 0.05) step *= 0.05 / step.norm();
    bool accepted = false;
    for (int halving = 0; halving < 6 && !accepted; ++halving, step /= 2) {
      const Eigen::VectorXd p_trial = Clip(params, result.p0, p + step, options);
      std::vector<SolvedTarget> trial = SolveAll(model, params, p_trial, targets, options, true);
      if (AllReached(trial) && MinSigma(trial) > sigma) {
        p = p_trial;
        solved = std::move(trial);
        accepted = true;
      }
    }
    if (!accepted) {
      result.message = "no design step raises the smallest sigma_min while keeping every target reached";
      break;
    }
  }

  result.p = p;
  result.iterations = it;
  result.final = Results(solved);
  result.converged = AllReached(solved) && MinSigma(solved) >= options.min_singular_value;
  if (result.converged) {
    result.message.clear();
  } else if (result.message.empty()) {
    result.message = AllReached(solved) ? "every target reached but sigma_min stays below the threshold"
                                        : "iteration limit reached before every target was reachable";
  }
  return result;
}

}  // namespace ccma
