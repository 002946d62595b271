#include "analyses/retime.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "analyses/internal/motion_limits.h"
#include "ccma/inertial_loads.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/internal/format.h"
#include "problems/forward_problem.h"
#include "problems/internal/control_motion.h"
#include "problems/internal/topp_ra.h"
#include "problems/natural_spline.h"

namespace ccma {
namespace {

using internal::MotionLimit;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMargin = 1e-3;        // TOPP-RA's limits shrunk by this (relative)
constexpr int kToppPasses = 10;         // TOPP-RA runs, each verified by ComputeDynamics
constexpr double kRoomSlack = 1.02;     // over the room a row beyond a limit must give up
constexpr double kScaleSlack = 1e-9;     // over the exact uniform stretch (rounding)
constexpr double kMaxDuration = 1e9;     // s: beyond, a limit leaves no room to move

// The model's constraints and the symbolic analysis every row's
// factorisation copies.
struct Constraints {
  explicit Constraints(const Model& model) : set(model), symbolic(set) {}
  const ConstraintSet set;
  const HessianSolver symbolic;
};

// Per row, along s = (t - t_0) / T: efforts a s'' + b s'^2 + c, rates u_s s'.
// Kept per row, the verification passes need no assembly and no
// factorisation: e = c + M Q_in(v, acc) with v, acc from the row's motion.
struct RowData {
  Eigen::VectorXd a, b, c, u_s;
  std::optional<State> s;          // the assembled configuration
  Eigen::VectorXd u;               // its controls (as assembled)
  std::shared_ptr<const ControlMotion> motion;  // its factorised J_s
  Eigen::MatrixXd M;               // efforts per generalized load (num_controls x tangent size)
};

// Dense entries all rows' factorisations may keep (doubles: 400 MB).
constexpr long kMaxKeptEntries = 50000000;

std::vector<RowData> PathData(const Model& model, const Constraints& constraints, const ControlPath& path,
                              std::optional<RetimeInfeasible>* failed) {
  const double T = path.times.back() - path.times.front();
  const NaturalCubicSpline spline(path.times, UnwrappedControls(model, path.controls));
  const EffortEvaluator evaluator(model);
  ForwardProblem forward(model);
  std::vector<RowData> rows;
  for (size_t r = 0; r < path.times.size(); ++r) {
    const ForwardResult assembly = forward.Assemble(path.controls[r]);
    if (!assembly.assembled) {
      RetimeInfeasible why;
      why.row = static_cast<int>(r);
      why.line = r < path.lines.size() ? path.lines[r] : 0;
      why.time = path.times[r];
      why.kind = "not assembled";
      *failed = why;
      return {};
    }
    const State& s = forward.state();
    CheckReachedPoint(model, s, path, r);
    RowData row;
    row.s = s;
    row.u = forward.controls();
    row.u_s = T * spline.KnotRate(static_cast<int>(r));
    const Eigen::VectorXd u_ss = T * T * spline.KnotAcceleration(static_cast<int>(r));
    auto motion = std::make_shared<const ControlMotion>(constraints.set, constraints.symbolic, s, forward.controls());
    const Eigen::VectorXd q_s = motion->Velocity(row.u_s);
    const Eigen::VectorXd q_ss = motion->Acceleration(row.u_s, u_ss, q_s);
    const Eigen::Index n = q_s.size();
    // The motion's factorisation: the statics, s'' q_s, s'^2 (q_ss, q_s x q_s) and every unit load.
    Eigen::MatrixXd Q(n, 3 + n);
    Q.col(0) = GeneralizedLoads(model, s);
    Q.col(1) = InertialLoads(model, s, Eigen::VectorXd::Zero(n), q_s);
    Q.col(2) = InertialLoads(model, s, q_s, q_ss);
    Q.rightCols(n).setIdentity();
    const Eigen::MatrixXd E = evaluator.EffortsUnder(s, forward.controls(), Q, motion->factorization());
    row.c = E.col(0);
    row.a = E.col(1);
    row.b = E.col(2);
    row.M = E.rightCols(n);
    const long kept = static_cast<long>(path.times.size()) * motion->factorization().stored_doubles();
    if (kept <= kMaxKeptEntries) row.motion = std::move(motion);
    rows.push_back(std::move(row));
  }
  return rows;
}

// Row r against `limit` at rest, as a report.
RetimeInfeasible Beyond(const ControlPath& path, const std::vector<RowData>& rows, const MotionLimit& limit, size_t r) {
  RetimeInfeasible why;
  why.row = static_cast<int>(r);
  why.line = r < path.lines.size() ? path.lines[r] : 0;
  why.time = path.times[r];
  why.control = limit.name;
  why.kind = internal::KindName(limit.kind);
  const Eigen::VectorXd& c = rows[r].c;
  why.effort = limit.controls.size() == 1 ? c[limit.controls[0]] : std::hypot(c[limit.controls[0]], c[limit.controls[1]]);
  why.lower = limit.lower;
  why.upper = limit.upper;
  return why;
}

// The first row and limit beyond it at rest (statics' own tolerance).
std::optional<RetimeInfeasible> AtRest(const ControlPath& path, const std::vector<RowData>& rows,
                                       const std::vector<MotionLimit>& limits) {
  for (size_t r = 0; r < rows.size(); ++r) {
    const Eigen::VectorXd still = Eigen::VectorXd::Zero(rows[r].c.size());
    for (const MotionLimit& limit : limits) {
      if (limit.kind == MotionLimit::Kind::kVelocity) continue;
      if (internal::Utilisation(limit, rows[r].c, still) <= 1 + 1e-12) continue;
      return Beyond(path, rows, limit, r);
    }
  }
  return std::nullopt;
}

// The stretch each row needs (and the limit that needs it) for efforts c +
// d and rates du: the largest RequiredStretch over the limits.
double RowStretch(const std::vector<MotionLimit>& limits, const Eigen::VectorXd& c, const Eigen::VectorXd& d,
                  const Eigen::VectorXd& du, int* which) {
  double k = 0;
  *which = -1;
  for (size_t l = 0; l < limits.size(); ++l) {
    const double need = internal::RequiredStretch(limits[l], c, d, du);
    if (need > k) k = need, *which = static_cast<int>(l);
  }
  return k;
}

std::vector<double> Positions(const ControlPath& path) {
  const double T = path.times.back() - path.times.front();
  std::vector<double> s;
  for (double t : path.times) s.push_back((t - path.times.front()) / T);
  s.back() = 1.0;
  return s;
}

// TOPP-RA over the rows: times from t_0, or empty when it finds no profile.
std::vector<double> ToppTiming(const ControlPath& path, const std::vector<RowData>& rows,
                               const std::vector<MotionLimit>& limits, const std::vector<double>& room,
                               double uniform_duration, std::vector<int>* active) {
  const std::vector<double> s = Positions(path);
  std::vector<internal::ToppStage> stages(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    stages[i].delta = i + 1 < rows.size() ? s[i + 1] - s[i] : 0.0;
    stages[i].x_max = kInf;
    for (size_t l = 0; l < limits.size(); ++l) {
      internal::AddStageConstraints(limits[l], static_cast<int>(l), rows[i].a, rows[i].b, rows[i].c, rows[i].u_s,
                                    kMargin, room[i], &stages[i]);
    }
  }
  // |s''| up to 1e8 times the scale 1 / T^2 of the uniform timing (or of
  // the input): far above any limit that binds, and it keeps the polygons'
  // numbers in range.
  const double u_bound = 1e8 / (uniform_duration * uniform_duration);
  const internal::ToppResult result = internal::ToppRa(stages, u_bound);
  if (!result.feasible) return {};
  // No limit active anywhere: only u_bound held the motion back, nothing bounds it.
  if (std::all_of(result.active.begin(), result.active.end(), [](int id) { return id < 0; })) return {};
  std::vector<double> times;
  try {
    times = internal::ToppTimes(s, result);
  } catch (const std::invalid_argument&) {  // a segment at rest at both ends: no timing
    return {};
  }
  for (double& t : times) t += path.times.front();
  *active = result.active;
  return times;
}

// Every row's stretch under the dynamics of the path at `times` (the
// efforts there are c + d with c the row's statics), and the largest.
// ComputeDynamics' numbers to rounding (the same spline and motion at the
// configurations PathData assembled as it does, and the same linear map
// from loads to efforts), without assembling or factorising again.
double NeededStretch(const Model& model, const Constraints& constraints, const ControlPath& path,
                     const std::vector<double>& times, const std::vector<RowData>& rows,
                     const std::vector<MotionLimit>& limits, std::vector<double>* per_row) {
  const NaturalCubicSpline spline(times, UnwrappedControls(model, path.controls));
  per_row->assign(rows.size(), 0.0);
  double k = 0;
  for (size_t r = 0; r < rows.size(); ++r) {
    const Eigen::VectorXd du = spline.KnotRate(static_cast<int>(r));
    const RowData& row = rows[r];
    std::optional<ControlMotion> fresh;  // when the row's factorisation was not kept
    if (!row.motion) fresh.emplace(constraints.set, constraints.symbolic, *row.s, row.u);
    const ControlMotion& motion = row.motion ? *row.motion : *fresh;
    const Eigen::VectorXd v = motion.Velocity(du);
    const Eigen::VectorXd acc = motion.Acceleration(du, spline.KnotAcceleration(static_cast<int>(r)), v);
    const Eigen::VectorXd d = row.M * InertialLoads(model, *row.s, v, acc);
    int which = -1;
    (*per_row)[r] = RowStretch(limits, row.c, d, du, &which);
    k = std::max(k, (*per_row)[r]);
  }
  return k;
}

std::vector<double> Stretched(const std::vector<double>& times, double k) {
  std::vector<double> out = times;
  for (double& t : out) t = times.front() + k * (t - times.front());
  return out;
}

// TOPP-RA's timing made to pass `ccma dynamics`, whose spline through the
// new times overshoots TOPP-RA's piecewise-constant s'' near its switches.
// Each pass verifies the timing; the pass's candidate is it stretched
// uniformly by the exact factor its worst row needs. Rows beyond a limit
// then leave the motion less room (by the square of their stretch: the
// motion's efforts go as s'^2) and TOPP-RA runs again. The fastest
// candidate wins. Empty when TOPP-RA finds no profile.
std::vector<double> VerifiedTopp(const Model& model, const Constraints& constraints, const ControlPath& path,
                                 const std::vector<RowData>& rows,
                                 const std::vector<MotionLimit>& limits, double scale, std::vector<int>* active,
                                 double* verified_scale) {
  std::vector<double> room(rows.size(), 1.0), best, need;
  for (int pass = 0; pass < kToppPasses; ++pass) {
    std::vector<int> pass_active;
    const std::vector<double> times = ToppTiming(path, rows, limits, room, scale, &pass_active);
    if (times.empty() || !std::isfinite(times.back())) break;
    const double k = NeededStretch(model, constraints, path, times, rows, limits, &need);
    // Within to rounding (ComputeDynamics may differ in the last bits): stretched a hair.
    const std::vector<double> candidate =
        k > 1 - kScaleSlack ? Stretched(times, std::max(k, 1.0) * (1 + kScaleSlack)) : times;
    if (best.empty() || candidate.back() < best.back()) {
      best = candidate;
      *active = pass_active;
      *verified_scale = (candidate.back() - candidate.front()) / (times.back() - times.front());
    }
    if (k <= 1) break;
    // The spline ties a row to its neighbours: they give up room too.
    std::vector<double> shrink(rows.size(), 1.0);
    for (size_t r = 0; r < rows.size(); ++r) {
      if (need[r] <= 1) continue;
      const double f = need[r] * need[r] * kRoomSlack;
      for (size_t n = r > 0 ? r - 1 : 0; n <= std::min(rows.size() - 1, r + 1); ++n) shrink[n] = std::max(shrink[n], f);
    }
    for (size_t r = 0; r < rows.size(); ++r) room[r] /= shrink[r];
  }
  return best;
}

// Per segment, the limit that binds at either end under the uniform
// stretch k (within 1e-3 of it), -1 where none does.
std::vector<int> UniformLimits(const std::vector<RowData>& rows, const std::vector<MotionLimit>& limits, double T,
                               double k) {
  std::vector<int> binding(rows.size(), -1);
  for (size_t r = 0; r < rows.size(); ++r) {
    int which = -1;
    const double need = RowStretch(limits, rows[r].c, rows[r].b / (T * T), rows[r].u_s / T, &which);
    if (need >= (1 - 1e-3) * k) binding[r] = which;
  }
  std::vector<int> out(rows.size() - 1, -1);
  for (size_t i = 0; i + 1 < rows.size(); ++i) out[i] = binding[i] >= 0 ? binding[i] : binding[i + 1];
  return out;
}

void Shares(const ControlPath& path, const std::vector<MotionLimit>& limits, RetimeReport* out) {
  const std::vector<double> s = Positions(path);
  std::vector<double> share(limits.size(), 0.0);
  for (size_t i = 0; i < out->segment_limits.size(); ++i) {
    if (out->segment_limits[i] >= 0) share[static_cast<size_t>(out->segment_limits[i])] += s[i + 1] - s[i];
  }
  for (size_t l = 0; l < limits.size(); ++l) {
    out->limit_names.push_back({limits[l].name, internal::KindName(limits[l].kind), 0.0});
    if (share[l] > 0) out->limiting.push_back({limits[l].name, internal::KindName(limits[l].kind), std::min(1.0, share[l])});
  }
  std::stable_sort(out->limiting.begin(), out->limiting.end(),
                   [](const RetimeLimitShare& x, const RetimeLimitShare& y) { return x.share > y.share; });
}

}  // namespace

RetimeReport Retime(const Model& model, const ControlPath& path) {
  const std::vector<MotionLimit> limits = internal::MotionLimits(model);
  if (limits.empty()) {
    throw std::invalid_argument(path.source + ": the model gives no effort_limits, push_limit or velocity_limit: "
                                "nothing bounds how fast the path may go");
  }
  RetimeReport out;
  out.original_duration = path.times.back() - path.times.front();
  const Constraints constraints(model);
  const std::vector<RowData> rows = PathData(model, constraints, path, &out.infeasible);
  if (out.infeasible) return out;
  out.infeasible = AtRest(path, rows, limits);
  if (out.infeasible) return out;

  // The best uniform scaling: at the input's timing s' = 1/T, s'' = 0.
  const double T = out.original_duration;
  double k_uniform = 0;
  size_t k_row = 0;
  int k_limit = -1;
  for (size_t r = 0; r < rows.size(); ++r) {
    int which = -1;
    const double need = RowStretch(limits, rows[r].c, rows[r].b / (T * T), rows[r].u_s / T, &which);
    if (need > k_uniform) k_uniform = need, k_row = r, k_limit = which;
  }
  if (!(k_uniform * T <= kMaxDuration)) {
    out.infeasible = Beyond(path, rows, limits[static_cast<size_t>(k_limit)], k_row);
    return out;
  }
  // k_uniform = 0: at the rows no limit feels a uniform speed-up (a path at
  // a constant rate has no acceleration there), so only a rest-to-rest
  // timing is bounded.
  std::vector<double> uniform;
  if (k_uniform > 0) {
    uniform = Stretched(path.times, k_uniform * (1 + kScaleSlack));
    out.uniform_duration = uniform.back() - uniform.front();
  }
  std::vector<int> active;
  const double scale = k_uniform > 0 ? out.uniform_duration : T;
  const std::vector<double> topp = rows.size() >= 3
                                       ? VerifiedTopp(model, constraints, path, rows, limits, scale, &active, &out.verified_scale)
                                       : std::vector<double>{};
  const bool topp_ok = !topp.empty() && std::isfinite(topp.back()) && topp.back() - topp.front() <= kMaxDuration;
  if (!topp_ok && uniform.empty()) {
    throw std::invalid_argument(path.source + ": no limit of the model bounds the speed along this path at its rows "
                                "(the limited controls neither move nor feel the motion's inertia there)");
  }
  if (topp_ok && (uniform.empty() || topp.back() - topp.front() < out.uniform_duration)) {
    out.method = "topp-ra";
    out.times = topp;
    out.segment_limits = active;
  } else {
    out.method = "uniform";
    out.times = uniform;
    out.segment_limits = UniformLimits(rows, limits, T, k_uniform);
  }
  out.duration = out.times.back() - out.times.front();
  out.feasible = true;
  Shares(path, limits, &out);
  return out;
}

}  // namespace ccma
