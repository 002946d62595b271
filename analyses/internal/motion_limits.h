// The limits `ccma retime` keeps (model_format.md: `effort_limits`,
// `push_limit`, `velocity_limit`), one list per model, and what each means
// for a row (analyses/retime.h, docs/dynamics.md "Retiming").
//
// A row's efforts are e = c + a s'' + b s'^2 along a path s (c: statics,
// a, b: the inertia of the path's motion) and its control rates u' = u_s s'.
// Each limit gives
// - Utilisation: how much of it a row uses (<= 1 within);
// - RequiredStretch: the smallest factor k by which stretching every time
//   interval (e -> c + d / k^2, u' -> u' / k, exact for a spline in time)
//   keeps the row within it (+inf when c alone is beyond it);
// - AddStageConstraints: its half-planes on (s'', s'^2) for TOPP-RA
//   (problems/internal/topp_ra.h), shrunk by a relative margin.
#ifndef CCMA_ANALYSES_INTERNAL_MOTION_LIMITS_H_
#define CCMA_ANALYSES_INTERNAL_MOTION_LIMITS_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "ccma/model.h"
#include "problems/internal/topp_ra.h"

namespace ccma::internal {

struct MotionLimit {
  enum class Kind { kEffort, kPush, kVelocity };
  Kind kind = Kind::kEffort;
  std::string name;           // the joint's or the base's
  std::vector<int> controls;  // 1, or 2 (a base's x and y: the norm is bounded)
  double lower = 0, upper = 0;  // kEffort: [lower, upper] [N or N*m]; kPush, kVelocity: the norm <= upper
};

const char* KindName(MotionLimit::Kind kind);  // "effort", "push", "velocity"

// Every limit of `model`: joints' effort_limits and velocity_limit, bases'
// push_limit (on x, y) and velocity_limit ([V on the norm of x', y', W on
// theta', then height', roll', pitch' for a legged base]).
std::vector<MotionLimit> MotionLimits(const Model& model);

// |e| / bound (push, velocity) or e's place in [lower, upper] (effort:
// 1 at either end), for efforts e and rates du (num_controls each).
double Utilisation(const MotionLimit& limit, const Eigen::VectorXd& e, const Eigen::VectorXd& du);

// The smallest k >= 0 with c + d / k^2 and du / k within the limit; 0 when
// any k is (a motion's part d at rounding level counts as none); +inf when c is not strictly within it (for an effort limit d
// pushing toward the end it sits at).
double RequiredStretch(const MotionLimit& limit, const Eigen::VectorXd& c, const Eigen::VectorXd& d,
                       const Eigen::VectorXd& du);

// Stage i's half-planes p s'' + q s'^2 <= r for e = a s'' + b s'^2 + c
// (push: an inscribed 32-gon), and x_max for u' = u_s s' (velocity), the
// limit shrunk by `margin` (relative) first, then the room it leaves the
// motion (the limit less c; for a rate, x_max) scaled by `room` in (0, 1].
// `id` is reported as active.
void AddStageConstraints(const MotionLimit& limit, int id, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                         const Eigen::VectorXd& c, const Eigen::VectorXd& u_s, double margin, double room,
                         ToppStage* stage);

}  // namespace ccma::internal

#endif  // CCMA_ANALYSES_INTERNAL_MOTION_LIMITS_H_
