// The fastest timing of a path within every effort and rate limit, rest to
// rest (cli.md, `ccma retime`; docs/dynamics.md, "Retiming").
//
// Method. The path is the input's rows (their configurations, in order),
// parameterised by s = (t - t_0) / T in [0, 1] through the same natural
// spline `ccma dynamics` reads. At each row, through one assembly and one
// factorisation, the efforts are affine in (s'', s'^2):
//   e = a s'' + b s'^2 + c   (c: statics; a, b: the inertia of the motion)
// and the control rates are u_s s'. Every limit (analyses/internal/
// motion_limits.h) is then a set of half-planes in (s'', s'^2), and TOPP-RA
// (problems/internal/topp_ra.h) gives the fastest rest-to-rest profile over
// the rows. `ccma dynamics` reads the output again through a natural spline
// in the new times, whose rates between rows differ from TOPP-RA's profile,
// so the timing is verified by ComputeDynamics: rows beyond a limit stretch
// their two intervals, once, then every interval is stretched by the exact
// factor that brings every row within (e = c + d / k^2 under a uniform
// stretch k). The best uniform scaling of the input is computed too, from
// the same data; the faster of the two verified timings is the answer.
#ifndef CCMA_ANALYSES_RETIME_H_
#define CCMA_ANALYSES_RETIME_H_

#include <optional>
#include <string>
#include <vector>

#include "analyses/dynamics.h"
#include "ccma/model.h"

namespace ccma {

// A limit and the fraction of the path (in s) where it is the one that
// sets the speed.
struct RetimeLimitShare {
  std::string name;  // the joint's or the base's
  std::string kind;  // "effort", "push" or "velocity"
  double share = 0;  // in [0, 1]
};

// Why a path cannot be retimed: a row beyond a limit at rest (or not
// assembled).
struct RetimeInfeasible {
  int row = 0;          // from 0
  int line = 0;         // in the input (0: unknown)
  double time = 0;      // the input's time_s [s]
  std::string control;  // the joint's or the base's name
  std::string kind;     // "effort", "push", or "not assembled"
  double effort = 0;    // at rest [N or N*m; push: the norm of x, y]
  double lower = 0, upper = 0;  // the limit (push: [0, push_limit])
};

struct RetimeReport {
  bool feasible = false;
  std::vector<double> times;     // per input row [s], from the input's first time
  double duration = 0;           // s
  double original_duration = 0;  // s
  // The best uniform scaling of the input [s]; 0 when no limit bounds it at
  // the rows (a path at a constant rate: no acceleration there).
  double uniform_duration = 0;
  std::string method;            // "topp-ra" or "uniform": the faster verified timing
  double verified_scale = 1;     // TOPP-RA's duration after verification / before
  std::vector<RetimeLimitShare> limiting;  // largest share first
  std::optional<RetimeInfeasible> infeasible;
  // Per segment of the answer: the limit that sets its speed (index into
  // limit_names, -1: none).
  std::vector<int> segment_limits;
  std::vector<RetimeLimitShare> limit_names;  // every limit of the model (share 0)
};

// Throws std::invalid_argument (bad input, exit 2) when the model gives no
// limit, no limit bounds the speed along the path, or the path is another
// model's (ComputeDynamics' check); infeasible is a result.
RetimeReport Retime(const Model& model, const ControlPath& path);

}  // namespace ccma

#endif  // CCMA_ANALYSES_RETIME_H_
