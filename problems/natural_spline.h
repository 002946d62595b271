// A natural cubic spline in time through vector-valued knots: the controls of
// a trajectory as a C2 curve (issue 52: `ccma dynamics` reads the rates and
// accelerations of the controls from it; `ccma retime` reads the path's
// derivatives from it).
//
// One cubic per component and per segment [t_i, t_{i+1}], h_i = t_{i+1} - t_i.
// The second derivatives at the knots, M_i, solve
//   h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1}
//     = 6 [(u_{i+1} - u_i) / h_i - (u_i - u_{i-1}) / h_{i-1}],  0 < i < N,
// with M_0 = M_N = 0 ("natural": no curvature imposed at the ends, which a CSV
// of rows cannot tell). The system is tridiagonal and strictly diagonally
// dominant, so the Thomas algorithm (no pivoting) is stable: O(N) for all
// components at once. Two knots give the straight line.
//
// Time scaling is exact: the spline through (k t_i, u_i) is u(t / k), so its
// rates are 1/k and its accelerations 1/k^2 of these (retime relies on it).
#ifndef CCMA_PROBLEMS_NATURAL_SPLINE_H_
#define CCMA_PROBLEMS_NATURAL_SPLINE_H_

#include <vector>

#include <Eigen/Core>

namespace ccma {

class NaturalCubicSpline {
 public:
  // Knots t_0 < ... < t_N [s] (N + 1 >= 2, finite, strictly increasing, with
  // finite differences) and values u_i (N + 1 vectors, all of one size, finite;
  // any unit). Throws std::invalid_argument naming the first bad knot.
  NaturalCubicSpline(std::vector<double> times, std::vector<Eigen::VectorXd> values);

  // u(t), u'(t) [unit/s], u''(t) [unit/s^2] at any finite t [s]. At a knot
  // t_i (i < N) the segment to its right is used (the value, rate and
  // acceleration are continuous there, so either side gives the same to
  // rounding). Outside [t_0, t_N] the end segment's cubic is extrapolated
  // (not the straight line a "natural" end suggests: callers that need
  // values outside the knots should not rely on them). Throws
  // std::invalid_argument on a non-finite t.
  Eigen::VectorXd Value(double t) const;
  Eigen::VectorXd Rate(double t) const;
  Eigen::VectorXd Acceleration(double t) const;

  // u'(t_i) and u''(t_i) = M_i at knot i in [0, knots()); throws
  // std::out_of_range otherwise.
  Eigen::VectorXd KnotRate(int i) const;
  Eigen::VectorXd KnotAcceleration(int i) const;

  int knots() const { return static_cast<int>(times_.size()); }
  double start() const { return times_.front(); }  // t_0 [s]
  double end() const { return times_.back(); }     // t_N [s]

 private:
  // The segment whose cubic is evaluated at t: i with t_i <= t < t_{i+1},
  // clamped into [0, N - 1].
  int Segment(double t) const;
  void CheckKnot(int i) const;

  std::vector<double> times_;
  std::vector<Eigen::VectorXd> values_;
  std::vector<Eigen::VectorXd> second_;  // M_i, per knot
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_NATURAL_SPLINE_H_
