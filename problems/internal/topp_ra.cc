#include "problems/internal/topp_ra.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "ccma/internal/format.h"
#include "problems/internal/convex_polygon.h"

namespace ccma {
namespace internal {
namespace {

constexpr double kToppInf = std::numeric_limits<double>::infinity();

std::string StageName(std::size_t i) { return "TOPP-RA: stage " + std::to_string(i); }

void CheckStages(const std::vector<ToppStage>& stages, double u_bound) {
  if (stages.size() < 3) {
    throw std::invalid_argument("TOPP-RA: needs at least 3 stages (2 segments), got " +
                                std::to_string(stages.size()));
  }
  if (!(u_bound > 0) || !std::isfinite(u_bound)) {
    throw std::invalid_argument("TOPP-RA: u_bound " + FormatG(u_bound) + " is not a positive finite number");
  }
  for (std::size_t i = 0; i < stages.size(); ++i) {
    const ToppStage& stage = stages[i];
    if (i + 1 < stages.size() && !(stage.delta > 0 && std::isfinite(stage.delta))) {
      throw std::invalid_argument(StageName(i) + ": delta " + FormatG(stage.delta) + " is not positive and finite");
    }
    if (i + 1 < stages.size() && !std::isfinite(2 * stage.delta * u_bound)) {
      throw std::invalid_argument(StageName(i) + ": delta " + FormatG(stage.delta) + " times u_bound overflows");
    }
    if (!(stage.x_max >= 0)) throw std::invalid_argument(StageName(i) + ": x_max " + FormatG(stage.x_max) + " is not >= 0");
    for (const HalfPlane& h : stage.constraints) {
      if (!std::isfinite(h.p) || !std::isfinite(h.q) || !std::isfinite(h.r)) {
        throw std::invalid_argument(StageName(i) + ": half-plane of limit " + std::to_string(h.limit_id) +
                                    " is not finite");
      }
    }
  }
}

// The u admitted by the stage's half-planes (and |u| <= u_bound) at a given
// x: [*lo, *hi]. Half-planes without u (p = 0) bound x only; false if one of
// them excludes x beyond rounding (the forward pass ignores that: x in K_i
// already satisfies them, to the clipping's rounding).
bool StageInterval(const ToppStage& stage, double x, double u_bound, double* lo, double* hi) {
  *lo = -u_bound;
  *hi = u_bound;
  bool x_admitted = true;
  for (const HalfPlane& h : stage.constraints) {
    const double rest = h.r - h.q * x;
    if (h.p > 0) {
      *hi = std::min(*hi, rest / h.p);
    } else if (h.p < 0) {
      *lo = std::max(*lo, rest / h.p);
    } else if (rest < -kClipSlack * (std::abs(h.q * x) + std::abs(h.r))) {
      x_admitted = false;
    }
  }
  return x_admitted;
}

// K_i from K_{i+1} = [next_lo, next_hi]: the polygon of (x, y = x_{i+1} =
// x + 2 delta u) over the box [0, X] x K_{i+1}, clipped by |u| <= u_bound and
// the stage's half-planes rewritten in (x, y): p u + q x <= r is
// (2 delta q - p) x + p y <= 2 delta r. In (x, y) the box's sides are the
// sets themselves (moderate numbers), not u_bound-sized. False if empty.
bool ControllableSet(const ToppStage& stage, double next_lo, double next_hi, double u_bound, Polygon* work,
                     Polygon* clipped, double* lo, double* hi) {
  const double two_delta = 2 * stage.delta;
  const double x_top = std::min(stage.x_max, next_hi + two_delta * u_bound);
  *work = BoxPolygon(0, x_top, next_lo, next_hi);
  ClipByHalfPlane(*work, -1, 1, two_delta * u_bound, clipped);  // u <= u_bound
  ClipByHalfPlane(*clipped, 1, -1, two_delta * u_bound, work);  // u >= -u_bound
  for (const HalfPlane& h : stage.constraints) {
    ClipByHalfPlane(*work, two_delta * h.q - h.p, h.p, two_delta * h.r, clipped);
    std::swap(*work, *clipped);
  }
  if (work->empty()) return false;
  XRange(*work, lo, hi);
  *lo = std::max(*lo, 0.0);
  *hi = std::min(*hi, x_top);
  return *lo <= *hi;
}

// K_N = {0} if the last stage admits some u at rest; then K_{N-1} .. K_0.
// False with result->failed_stage set at the first empty set.
bool BackwardPass(const std::vector<ToppStage>& stages, double u_bound, ToppResult* result) {
  const int n = static_cast<int>(stages.size()) - 1;
  result->k_min.assign(n + 1, 0.0);
  result->k_max.assign(n + 1, 0.0);
  double lo = 0, hi = 0;
  if (!StageInterval(stages[n], 0.0, u_bound, &lo, &hi) || lo > hi) {
    result->failed_stage = n;
    return false;
  }
  Polygon work, clipped;
  for (int i = n - 1; i >= 0; --i) {
    if (!ControllableSet(stages[i], result->k_min[i + 1], result->k_max[i + 1], u_bound, &work, &clipped,
                         &result->k_min[i], &result->k_max[i])) {
      result->failed_stage = i;
      return false;
    }
  }
  // The path cannot start from rest (beyond the clipping's rounding).
  if (result->k_min[0] > kClipSlack * result->k_max[0]) {
    result->failed_stage = 0;
    return false;
  }
  return true;
}

// From x_0 = 0: the largest u admitted at (stage i, x_i) that keeps x_{i+1}
// in K_{i+1}. x_{i+1} is clamped into K_{i+1} against rounding, and u then
// recomputed from it, so that x_{i+1} = x_i + 2 delta u_i holds to rounding.
void ForwardPass(const std::vector<ToppStage>& stages, double u_bound, ToppResult* result) {
  const int n = static_cast<int>(stages.size()) - 1;
  result->x.assign(n + 1, 0.0);
  result->u.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const double x = result->x[i], two_delta = 2 * stages[i].delta;
    double lo = 0, hi = 0;
    StageInterval(stages[i], x, u_bound, &lo, &hi);
    const double u = std::min(hi, (result->k_max[i + 1] - x) / two_delta);
    const double next = x + two_delta * u;
    const double clamped = std::clamp(next, result->k_min[i + 1], result->k_max[i + 1]);
    result->x[i + 1] = clamped;
    result->u[i] = clamped == next ? u : (clamped - x) / two_delta;
  }
  result->x[n] = 0;  // K_N = {0}: the clamp gave 0 already
}

// The limit tight at (x, u) on a stage, the tightest relative to its terms;
// -1 if none is within kToppTight.
int TightLimit(const ToppStage& stage, double x, double u) {
  int best = -1;
  double best_ratio = kToppInf;
  auto consider = [&](double slack, double scale, int id) {
    const double ratio = std::abs(slack) / std::max(scale, std::numeric_limits<double>::min());
    if (id >= 0 && ratio <= kToppTight && ratio < best_ratio) {
      best = id;
      best_ratio = ratio;
    }
  };
  for (const HalfPlane& h : stage.constraints) {
    consider(h.r - h.p * u - h.q * x, std::abs(h.p * u) + std::abs(h.q * x) + std::abs(h.r), h.limit_id);
  }
  if (std::isfinite(stage.x_max)) consider(stage.x_max - x, stage.x_max, stage.x_max_id);
  return best;
}

// Backward over the segments, so that a segment braked by a limit ahead
// (x_{i+1} at the top of K_{i+1}, no limit of its own tight) inherits it.
std::vector<int> ActiveLimits(const std::vector<ToppStage>& stages, const ToppResult& result) {
  const int n = static_cast<int>(stages.size()) - 1;
  std::vector<int> active(n, -1);
  for (int i = n - 1; i >= 0; --i) {
    active[i] = TightLimit(stages[i], result.x[i], result.u[i]);
    const double top = result.k_max[i + 1];
    if (active[i] < 0 && i + 1 < n && result.x[i + 1] >= top - kToppTight * top) active[i] = active[i + 1];
  }
  return active;
}

}  // namespace

ToppResult ToppRa(const std::vector<ToppStage>& stages, double u_bound) {
  CheckStages(stages, u_bound);
  ToppResult result;
  if (!BackwardPass(stages, u_bound, &result)) return result;
  result.feasible = true;
  ForwardPass(stages, u_bound, &result);
  result.active = ActiveLimits(stages, result);
  return result;
}

std::vector<double> ToppTimes(const std::vector<double>& s, const ToppResult& result) {
  if (!result.feasible) throw std::invalid_argument("TOPP-RA times: the result is infeasible");
  if (s.size() != result.x.size() || result.u.size() + 1 != s.size() || s.size() < 3) {
    throw std::invalid_argument("TOPP-RA times: " + std::to_string(s.size()) + " positions for " +
                                std::to_string(result.x.size()) + " stages");
  }
  std::vector<double> t(s.size(), 0.0);
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    const double delta = s[i + 1] - s[i];
    const double rates = std::sqrt(result.x[i]) + std::sqrt(result.x[i + 1]);
    if (!(delta > 0)) throw std::invalid_argument("TOPP-RA times: position " + std::to_string(i + 1) + " not after the previous");
    if (!(rates > 0)) {
      throw std::invalid_argument("TOPP-RA times: segment " + std::to_string(i) + " is at rest at both ends");
    }
    t[i + 1] = t[i] + 2 * delta / rates;
  }
  return t;
}

}  // namespace internal
}  // namespace ccma
