// The natural cubic spline of the controls in time (problems/natural_spline.h):
// straight lines reproduced, the knots interpolated, C2 at interior knots
// (left limits by an exact Taylor expansion of the left cubic), zero curvature
// at both ends, exact time scaling, a 4-knot example solved by hand, the end
// cubics extrapolated, bad input rejected.
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "problems/natural_spline.h"

namespace ccma {
namespace natural_spline_test {

struct Knots {
  std::vector<double> times;
  std::vector<Eigen::VectorXd> values;
};

// n + 1 knots with uneven intervals in [0.1, 2) s starting at t0, values in
// [-3, 3) with `dim` components.
Knots RandomKnots(int n, int dim, double t0, std::mt19937* rng) {
  std::uniform_real_distribution<double> interval(0.1, 2.0), value(-3.0, 3.0);
  Knots k;
  double t = t0;
  for (int i = 0; i <= n; ++i) {
    if (i > 0) t += interval(*rng);
    k.times.push_back(t);
    Eigen::VectorXd v(dim);
    for (int c = 0; c < dim; ++c) v[c] = value(*rng);
    k.values.push_back(v);
  }
  return k;
}

double Scale(const Knots& k) {
  double s = 1;
  for (const auto& v : k.values) s = std::max(s, v.cwiseAbs().maxCoeff());
  return s;
}

void ExpectNear(const Eigen::VectorXd& actual, const Eigen::VectorXd& expected, double tolerance,
                const std::string& what) {
  ASSERT_EQ(actual.size(), expected.size()) << what;
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), tolerance) << what << "\nactual   " << actual.transpose()
                                                                  << "\nexpected " << expected.transpose();
}

TEST(NaturalSpline, ReproducesStraightLines) {
  std::mt19937 rng{52001};
  std::uniform_real_distribution<double> coefficient(-2.0, 2.0), where(-1.0, 1.0);
  for (int n : {1, 2, 3, 7, 40}) {
    Knots k = RandomKnots(n, 3, -1.5, &rng);
    const Eigen::Vector3d a{coefficient(rng), coefficient(rng), coefficient(rng)};
    const Eigen::Vector3d b{coefficient(rng), coefficient(rng), coefficient(rng)};
    for (int i = 0; i <= n; ++i) k.values[i] = a + b * k.times[i];
    const NaturalCubicSpline spline(k.times, k.values);
    const double span = spline.end() - spline.start();
    // Inside and (by the end cubics, which are straight here) outside.
    for (int j = 0; j < 20; ++j) {
      const double t = spline.start() + span * (0.5 + 0.75 * where(rng));
      const double scale = (a.cwiseAbs() + b.cwiseAbs() * std::abs(t)).maxCoeff();
      ExpectNear(spline.Value(t), a + b * t, 1e-12 * scale, "value, n = " + std::to_string(n));
      ExpectNear(spline.Rate(t), b, 1e-12 * scale, "rate");
      ExpectNear(spline.Acceleration(t), Eigen::Vector3d::Zero(), 1e-12 * scale, "acceleration");
    }
    for (int i = 0; i <= n; ++i) ExpectNear(spline.KnotRate(i), b, 1e-12 * a.cwiseAbs().maxCoeff() + 1e-12, "knot");
  }
}

TEST(NaturalSpline, InterpolatesTheKnotsAndItsKnotRatesAreItsRates) {
  std::mt19937 rng{52002};
  const Knots k = RandomKnots(12, 2, 3.0, &rng);
  const NaturalCubicSpline spline(k.times, k.values);
  ASSERT_EQ(spline.knots(), 13);
  EXPECT_EQ(spline.start(), k.times.front());
  EXPECT_EQ(spline.end(), k.times.back());
  for (int i = 0; i < spline.knots(); ++i) {
    ExpectNear(spline.Value(k.times[i]), k.values[i], 1e-14 * Scale(k), "value at knot " + std::to_string(i));
    ExpectNear(spline.KnotRate(i), spline.Rate(k.times[i]), 1e-12 * Scale(k), "rate at knot " + std::to_string(i));
    ExpectNear(spline.KnotAcceleration(i), spline.Acceleration(k.times[i]), 1e-12 * Scale(k), "acceleration");
  }
}

// Left limits at t_i of the cubic of segment i - 1, from its own values at
// two inner points by the exact Taylor expansion of a cubic; right limits are
// the spline's values at t_i (segment i). Left and right must agree: that is
// the equation the second derivatives solve.
TEST(NaturalSpline, IsTwiceContinuouslyDifferentiableAtInteriorKnots) {
  std::mt19937 rng{52003};
  const Knots k = RandomKnots(9, 3, 0.0, &rng);
  const NaturalCubicSpline spline(k.times, k.values);
  for (int i = 1; i + 1 < spline.knots(); ++i) {
    const double d = (k.times[i] - k.times[i - 1]) / 2, m = k.times[i] - d;
    const Eigen::VectorXd jerk = (spline.Acceleration(m + d / 2) - spline.Acceleration(m)) / (d / 2);
    const Eigen::VectorXd value = spline.Value(m) + d * spline.Rate(m) + d * d / 2 * spline.Acceleration(m) +
                                  d * d * d / 6 * jerk;
    const Eigen::VectorXd rate = spline.Rate(m) + d * spline.Acceleration(m) + d * d / 2 * jerk;
    const Eigen::VectorXd acceleration = spline.Acceleration(m) + d * jerk;
    const double t = k.times[i];
    const double scale = spline.Value(t).cwiseAbs().maxCoeff() + spline.Rate(t).cwiseAbs().maxCoeff() +
                         spline.Acceleration(t).cwiseAbs().maxCoeff();
    const std::string knot = " at knot " + std::to_string(i);
    ExpectNear(value, spline.Value(t), 1e-12 * scale, "value" + knot);
    ExpectNear(rate, spline.Rate(t), 1e-12 * scale, "rate" + knot);
    ExpectNear(acceleration, spline.Acceleration(t), 1e-12 * scale, "acceleration" + knot);
  }
}

TEST(NaturalSpline, HasNoCurvatureAtItsEnds) {
  std::mt19937 rng{52004};
  for (int n : {1, 2, 5, 30}) {
    const Knots k = RandomKnots(n, 2, -4.0, &rng);
    const NaturalCubicSpline spline(k.times, k.values);
    EXPECT_EQ(spline.KnotAcceleration(0), Eigen::Vector2d::Zero());
    EXPECT_EQ(spline.KnotAcceleration(n), Eigen::Vector2d::Zero());
    ExpectNear(spline.Acceleration(spline.start()), Eigen::Vector2d::Zero(), 1e-12 * Scale(k), "at t_0");
    ExpectNear(spline.Acceleration(spline.end()), Eigen::Vector2d::Zero(), 1e-12 * Scale(k), "at t_N");
  }
}

// The spline through (k t_i, u_i) is u(t / k): the retiming of a path by a
// uniform factor changes rates by 1/k and accelerations by 1/k^2 exactly.
TEST(NaturalSpline, ScalesExactlyWithTime) {
  std::mt19937 rng{52005};
  std::uniform_real_distribution<double> where(0.0, 1.0);
  const Knots k = RandomKnots(15, 2, 0.7, &rng);
  const NaturalCubicSpline spline(k.times, k.values);
  for (double factor : {3.7, 0.01, 1000.0}) {
    std::vector<double> scaled;
    for (double t : k.times) scaled.push_back(factor * t);
    const NaturalCubicSpline slow(scaled, k.values);
    for (int j = 0; j < 30; ++j) {
      const double t = spline.start() + (spline.end() - spline.start()) * where(rng);
      const double s = Scale(k) + spline.Rate(t).cwiseAbs().maxCoeff() + spline.Acceleration(t).cwiseAbs().maxCoeff();
      ExpectNear(slow.Value(factor * t), spline.Value(t), 1e-12 * s, "value");
      ExpectNear(slow.Rate(factor * t) * factor, spline.Rate(t), 1e-12 * s, "rate");
      ExpectNear(slow.Acceleration(factor * t) * factor * factor, spline.Acceleration(t), 1e-12 * s, "acceleration");
    }
  }
}

// Knots t = 0, 1, 3, 4 (h = 1, 2, 1), u = 0, 1, 0, 2; M_0 = M_3 = 0:
//   i = 1: 6 M_1 + 2 M_2 = 6 [(0 - 1)/2 - (1 - 0)/1] = -9
//   i = 2: 2 M_1 + 6 M_2 = 6 [(2 - 0)/1 - (0 - 1)/2] = 15
// 3 x (i = 1) - (i = 2): 16 M_1 = -42, M_1 = -21/8; M_2 = (15 + 21/4)/6 = 27/8.
// Knot rates: u'_0 = 1 - (2 M_0 + M_1)/6 = 23/16; u'_1 = -1/2 - 2 (2 M_1 + M_2)/6
// = 1/8; u'_2 = 2 - (2 M_2 + M_3)/6 = 7/8; u'_3 = 2 + (M_2 + 2 M_3)/6 = 41/16.
// At t = 2 (a = b = 1/2, h = 2): u = 1/2 - (3/8)(M_1 + M_2)(4/6) = 5/16,
// u' = -1/2 + [-(3/4 - 1) M_1 + (3/4 - 1) M_2] (2/6) = -1/2 + (M_1 - M_2)/12 = -1,
// u'' = (M_1 + M_2)/2 = 3/8.
// Extrapolated (end cubics, Taylor from the end knot with jerk (M_3 - M_2)/1
// = -27/8 and (M_1 - M_0)/1 = -21/8):
//   u(5) = 2 + 41/16 - (27/8)/6 = 4,  u'(5) = 41/16 - (27/8)/2 = 7/8,
//   u''(5) = -27/8;  u(-1) = -23/16 + (21/8)/6 = -1, u''(-1) = 21/8.
// The second component is 2 u + 3 (the spline is linear in the data).
TEST(NaturalSpline, MatchesAFourKnotExampleSolvedByHand) {
  std::vector<Eigen::VectorXd> values;
  for (double u : {0.0, 1.0, 0.0, 2.0}) values.push_back(Eigen::Vector2d{u, 2 * u + 3});
  const NaturalCubicSpline spline({0.0, 1.0, 3.0, 4.0}, values);
  auto pair = [](double u, double offset) { return Eigen::Vector2d{u, 2 * u + offset}; };
  const double tol = 1e-14;
  const double M[] = {0.0, -21.0 / 8, 27.0 / 8, 0.0};
  const double rates[] = {23.0 / 16, 1.0 / 8, 7.0 / 8, 41.0 / 16};
  for (int i = 0; i < 4; ++i) {
    ExpectNear(spline.KnotAcceleration(i), pair(M[i], 0), tol, "M_" + std::to_string(i));
    ExpectNear(spline.KnotRate(i), pair(rates[i], 0), tol, "u'_" + std::to_string(i));
  }
  ExpectNear(spline.Value(2.0), pair(5.0 / 16, 3), tol, "u(2)");
  ExpectNear(spline.Rate(2.0), pair(-1.0, 0), tol, "u'(2)");
  ExpectNear(spline.Acceleration(2.0), pair(3.0 / 8, 0), tol, "u''(2)");
  ExpectNear(spline.Value(5.0), pair(4.0, 3), 4 * tol, "u(5)");
  ExpectNear(spline.Rate(5.0), pair(7.0 / 8, 0), 4 * tol, "u'(5)");
  ExpectNear(spline.Acceleration(5.0), pair(-27.0 / 8, 0), 4 * tol, "u''(5)");
  ExpectNear(spline.Value(-1.0), pair(-1.0, 3), 4 * tol, "u(-1)");
  ExpectNear(spline.Acceleration(-1.0), pair(21.0 / 8, 0), 4 * tol, "u''(-1)");
}

void ExpectRejected(std::vector<double> times, std::vector<Eigen::VectorXd> values, const std::string& part) {
  try {
    NaturalCubicSpline spline(std::move(times), std::move(values));
    ADD_FAILURE() << "accepted; expected a message with '" << part << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(NaturalSpline, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const Eigen::VectorXd one = Eigen::Vector2d{1, 2}, other = Eigen::Vector2d{3, 4};
  ExpectRejected({}, {}, "at least 2 knots, got 0");
  ExpectRejected({0.0}, {one}, "at least 2 knots, got 1");
  ExpectRejected({0.0, 1.0}, {one}, "2 times but 1 values");
  ExpectRejected({0.0, 1.0, 2.0}, {one, other, Eigen::Vector3d{1, 2, 3}}, "knot 2: 3 components, knot 0 has 2");
  ExpectRejected({0.0, nan, 2.0}, {one, other, one}, "knot 1: time is not finite");
  ExpectRejected({0.0, 1.0, inf}, {one, other, one}, "knot 2: time is not finite");
  ExpectRejected({0.0, 1.0}, {one, Eigen::Vector2d{1, nan}}, "knot 1: a value is not finite");
  ExpectRejected({0.0, 1.0, 1.0}, {one, other, one}, "knot 2: time 1 is not after the previous 1");
  ExpectRejected({0.0, 2.0, 1.5}, {one, other, one}, "knot 2: time 1.5 is not after the previous 2");
  ExpectRejected({-1e308, 1e308}, {one, other}, "knot 1: interval to the previous knot overflows");

  const NaturalCubicSpline spline({0.0, 1.0, 2.0}, {one, other, one});
  EXPECT_THROW(spline.Value(nan), std::invalid_argument);
  EXPECT_THROW(spline.Rate(inf), std::invalid_argument);
  EXPECT_THROW(spline.KnotRate(-1), std::out_of_range);
  EXPECT_THROW(spline.KnotAcceleration(3), std::out_of_range);
  EXPECT_NO_THROW(spline.KnotRate(2));
}

}  // namespace natural_spline_test
}  // namespace ccma
