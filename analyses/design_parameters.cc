// Design parameters (analyses/design.h): naming them, applying them to a
// model, their exact sensitivities, and writing them back into the model text.
#include "analyses/design.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <yaml-cpp/yaml.h>

#include "ccma/internal/constraint_set.h"
#include "formats/model_loader.h"
#include "problems/internal/sensitivity.h"

namespace ccma {
namespace {

// Pivot ratio below which dG/ds counts as singular (as in sensitivity.cc).
constexpr double kSingularRcond = 1e-12;
// Step of the central difference of G in p [m]. G is quadratic in p, so the
// difference is exact for any h; 1e-3 keeps rounding (~eps |G| / h) tiny.
constexpr double kGradientStep = 1e-3;
// Distinct home points: two joints closer than this cannot define a length.
constexpr double kMinAnchorDistance = 1e-9;

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
  // A joint is varied by one item (docs/design.md): `.point` names all three
  // coordinates, so `J.x` and `J.z` together are refused like `J.z` twice.
  if (IsVaried(*params, joint) || IsAnchor(*params, joint)) {
    *why = "'" + item + "': the point of joint '" + name +
           "' is already varied or anchors a length (vary a joint once; JOINT.point varies x, y and z)";
    return false;
  }
  for (int axis : axes) {
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
  // yaml-cpp skips a UTF-8 byte-order mark and counts its marks from the
  // first character after it: patch the text after the mark and keep the
  // mark, so that a file saved with one is patched where its numbers are.
  static const std::string kUtf8Bom = "\xEF\xBB\xBF";
  if (text.compare(0, kUtf8Bom.size(), kUtf8Bom) == 0) {
    return kUtf8Bom + PatchModelText(text.substr(kUtf8Bom.size()), original, designed, params);
  }
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

bool AddDesignParameters(const Model& model, const std::vector<std::string>& vary,
                         const std::vector<std::string>& vary_length, DesignParameters* params, std::string* why) {
  for (const std::string& item : vary) {
    if (!AddJointCoordinates(model, item, params, why)) {
      *why = "vary: " + *why;
      return false;
    }
  }
  for (const std::string& item : vary_length) {
    if (!AddLinkLength(model, item, params, why)) {
      *why = "vary_length: " + *why;
      return false;
    }
  }
  return true;
}

}  // namespace ccma
