// Time-optimal path parameterisation by reachability analysis (TOPP-RA, Pham
// and Pham 2018), model-free: the fastest rest-to-rest motion along a path
// s in [s_0, s_N] whose limits, at each grid point ("stage") i, are linear in
//   u = s''   (path acceleration [unit/s^2], constant on segment [s_i, s_{i+1}])
//   x = s'^2  (squared path rate [unit^2/s^2] at s_i),
// as the efforts of a mechanism moving along a path are (issue 52: `ccma
// retime` builds the stages from its dynamics; docs/dynamics.md).
//
// With u constant on a segment, x_{i+1} = x_i + 2 delta_i u_i exactly.
// Backward pass: K_N = {0} (rest); K_i = the x of stage i from which some
// admissible u reaches K_{i+1}, an interval [min x, max x] over a convex
// polygon (convex_polygon.h). Forward pass: from x_0 = 0, the largest
// admissible u that keeps x_{i+1} in K_{i+1}; this greedy profile is
// time-optimal for the discretised problem (the paper's Theorem 1).
#ifndef CCMA_PROBLEMS_INTERNAL_TOPP_RA_H_
#define CCMA_PROBLEMS_INTERNAL_TOPP_RA_H_

#include <vector>

namespace ccma {
namespace internal {

// p u + q x <= r, u [unit/s^2], x [unit^2/s^2]. limit_id: the caller's name
// for the limit (>= 0), reported in ToppResult::active.
struct HalfPlane {
  double p, q, r;
  int limit_id;
};

struct ToppStage {
  double delta;   // s_{i+1} - s_i > 0 [unit]; unused on the last stage
  double x_max;   // bound on x at this stage (>= 0, may be +inf): rate limits
  std::vector<HalfPlane> constraints;  // at this stage, on (u_i, x_i)
  int x_max_id = -1;  // limit_id reported where x = x_max is tight (-1: none)
};

struct ToppResult {
  bool feasible = false;
  int failed_stage = -1;   // the stage whose set is empty (or 0: x_0 = 0 not in K_0)
  std::vector<double> x;   // N + 1 values s'^2 at the stages (x_0 = x_N = 0)
  std::vector<double> u;   // N values s'' on the segments
  // Per segment: limit_id of the half-plane (or of x_max) tight at (x_i, u_i)
  // within kToppTight relative (the tightest if several); if none is but
  // x_{i+1} is at the top of K_{i+1} (a limit further on brakes this
  // segment), the next segment's; -1 if neither (the caller's u_bound, or the
  // last segment when the switch to braking falls inside it).
  std::vector<int> active;
  // The controllable sets K_i = [k_min[i], k_max[i]] (N + 1 each; only
  // stages after failed_stage are meaningful when infeasible).
  std::vector<double> k_min, k_max;
};

constexpr double kToppTight = 1e-7;

// N + 1 stages (N >= 2 segments: with one segment both ends at rest leave no
// rate to move with; split it), |u| <= u_bound > 0 (a box that keeps the
// polygons bounded: make it far above any real limit, e.g. 1e12). The last
// stage's x_max is not used (x_N = 0); its constraints must admit some u at
// rest, else failed_stage = N. Throws std::invalid_argument on fewer than 3
// stages, a delta not > 0, a negative or NaN x_max, non-finite half-planes or
// a bad u_bound. Infeasible is a result (feasible = false), not an exception.
ToppResult ToppRa(const std::vector<ToppStage>& stages, double u_bound);

// Cumulative times [s] at the stages of a feasible result (N + 1, from 0),
// s = the stages' positions (N + 1, increasing; s_{i+1} - s_i the deltas):
// dt_i = 2 delta_i / (sqrt(x_i) + sqrt(x_{i+1})), exact for constant s''.
// Throws std::invalid_argument on an infeasible result, mismatched sizes or a
// segment at rest at both ends (it would take forever).
std::vector<double> ToppTimes(const std::vector<double>& s, const ToppResult& result);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_TOPP_RA_H_
