#include "problems/natural_spline.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "ccma/internal/format.h"

namespace ccma {
namespace {

std::string KnotName(std::size_t i) { return "spline: knot " + std::to_string(i); }

// Rejects what would make the spline meaningless or non-finite: too few
// knots, mismatched sizes, non-finite entries, times not increasing (or so far
// apart that their difference overflows).
void CheckKnots(const std::vector<double>& times, const std::vector<Eigen::VectorXd>& values) {
  if (times.size() < 2) {
    throw std::invalid_argument("spline: needs at least 2 knots, got " + std::to_string(times.size()));
  }
  if (values.size() != times.size()) {
    throw std::invalid_argument("spline: " + std::to_string(times.size()) + " times but " +
                                std::to_string(values.size()) + " values");
  }
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (!std::isfinite(times[i])) throw std::invalid_argument(KnotName(i) + ": time is not finite");
    if (values[i].size() != values[0].size()) {
      throw std::invalid_argument(KnotName(i) + ": " + std::to_string(values[i].size()) +
                                  " components, knot 0 has " + std::to_string(values[0].size()));
    }
    if (!values[i].allFinite()) throw std::invalid_argument(KnotName(i) + ": a value is not finite");
    if (i == 0) continue;
    const double h = times[i] - times[i - 1];
    if (!(h > 0)) {
      throw std::invalid_argument(KnotName(i) + ": time " + FormatExact(times[i]) + " is not after the previous " +
                                  FormatExact(times[i - 1]));
    }
    if (!std::isfinite(h)) throw std::invalid_argument(KnotName(i) + ": interval to the previous knot overflows");
  }
}

}  // namespace

NaturalCubicSpline::NaturalCubicSpline(std::vector<double> times, std::vector<Eigen::VectorXd> values) {
  CheckKnots(times, values);
  times_ = std::move(times);
  values_ = std::move(values);
  const int n = knots() - 1;  // segments
  const Eigen::Index dim = values_[0].size();
  second_.assign(n + 1, Eigen::VectorXd::Zero(dim));
  if (n < 2) return;  // two knots: the straight line, M_0 = M_1 = 0
  // Thomas algorithm on the interior unknowns M_1 .. M_{n-1}: forward
  // elimination keeps the modified super-diagonal c' and right-hand sides d'.
  std::vector<double> c(n);
  std::vector<Eigen::VectorXd> d(n);
  auto h = [&](int i) { return times_[i + 1] - times_[i]; };
  auto slope = [&](int i) -> Eigen::VectorXd { return (values_[i + 1] - values_[i]) / h(i); };
  for (int j = 1; j < n; ++j) {
    const double sub = j > 1 ? h(j - 1) : 0.0;
    const double pivot = 2 * (h(j - 1) + h(j)) - (j > 1 ? sub * c[j - 1] : 0.0);
    c[j] = h(j) / pivot;
    d[j] = 6 * (slope(j) - slope(j - 1));
    if (j > 1) d[j] -= sub * d[j - 1];
    d[j] /= pivot;
  }
  second_[n - 1] = d[n - 1];
  for (int j = n - 2; j >= 1; --j) second_[j] = d[j] - c[j] * second_[j + 1];
}

int NaturalCubicSpline::Segment(double t) const {
  if (!std::isfinite(t)) throw std::invalid_argument("spline: time " + FormatG(t) + " is not finite");
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  const int i = static_cast<int>(after - times_.begin()) - 1;
  return std::clamp(i, 0, knots() - 2);
}

// On segment i with a = (t_{i+1} - t) / h, b = (t - t_i) / h (a + b = 1):
//   u   = a u_i + b u_{i+1} + [(a^3 - a) M_i + (b^3 - b) M_{i+1}] h^2 / 6
//   u'  = (u_{i+1} - u_i) / h + [-(3 a^2 - 1) M_i + (3 b^2 - 1) M_{i+1}] h / 6
//   u'' = a M_i + b M_{i+1}
// These are polynomials in t, so the same formulas extrapolate.
Eigen::VectorXd NaturalCubicSpline::Value(double t) const {
  const int i = Segment(t);
  const double h = times_[i + 1] - times_[i];
  const double a = (times_[i + 1] - t) / h, b = (t - times_[i]) / h;
  return a * values_[i] + b * values_[i + 1] +
         ((a * a * a - a) * second_[i] + (b * b * b - b) * second_[i + 1]) * (h * h / 6);
}

Eigen::VectorXd NaturalCubicSpline::Rate(double t) const {
  const int i = Segment(t);
  const double h = times_[i + 1] - times_[i];
  const double a = (times_[i + 1] - t) / h, b = (t - times_[i]) / h;
  return (values_[i + 1] - values_[i]) / h +
         (-(3 * a * a - 1) * second_[i] + (3 * b * b - 1) * second_[i + 1]) * (h / 6);
}

Eigen::VectorXd NaturalCubicSpline::Acceleration(double t) const {
  const int i = Segment(t);
  const double h = times_[i + 1] - times_[i];
  const double a = (times_[i + 1] - t) / h, b = (t - times_[i]) / h;
  return a * second_[i] + b * second_[i + 1];
}

void NaturalCubicSpline::CheckKnot(int i) const {
  if (i < 0 || i >= knots()) {
    throw std::out_of_range("spline: knot " + std::to_string(i) + " of " + std::to_string(knots()));
  }
}

// The rate formula at a = 1, b = 0 of segment i (or a = 0, b = 1 of the last
// segment at t_N), without rounding a and b.
Eigen::VectorXd NaturalCubicSpline::KnotRate(int i) const {
  CheckKnot(i);
  const int n = knots() - 1;
  if (i == n) {
    const double h = times_[n] - times_[n - 1];
    return (values_[n] - values_[n - 1]) / h + (second_[n - 1] + 2 * second_[n]) * (h / 6);
  }
  const double h = times_[i + 1] - times_[i];
  return (values_[i + 1] - values_[i]) / h - (2 * second_[i] + second_[i + 1]) * (h / 6);
}

Eigen::VectorXd NaturalCubicSpline::KnotAcceleration(int i) const {
  CheckKnot(i);
  return second_[i];
}

}  // namespace ccma
