// TOPP-RA, model-free (problems/internal/topp_ra.h) and its convex polygon
// clipping (problems/internal/convex_polygon.h): closed forms for the double
// integrator (bang-bang, and with a rate limit: accelerate, cruise, brake), a
// drag-like limit u + c x <= A against its closed form, infeasible stages
// reported, the forward profile within every half-plane, and which limit is
// reported active where (including a segment braked by a limit ahead).
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "problems/internal/convex_polygon.h"
#include "problems/internal/topp_ra.h"

namespace ccma {
namespace internal {
namespace topp_ra_test {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kUBound = 1e12;
enum Limit { kAccelerate = 0, kBrake = 1, kRate = 2, kRateHalfPlane = 5 };

// `count` stages uniform on [0, length]; x_max = v2 (id kRate).
std::vector<ToppStage> UniformStages(int count, double length, double v2) {
  std::vector<ToppStage> stages(count);
  for (ToppStage& stage : stages) {
    stage.delta = length / (count - 1);
    stage.x_max = v2;
    stage.x_max_id = kRate;
  }
  return stages;
}

// |s''| <= a on every stage.
std::vector<ToppStage> DoubleIntegrator(int count, double length, double a, double v2 = kInf) {
  std::vector<ToppStage> stages = UniformStages(count, length, v2);
  for (ToppStage& stage : stages) stage.constraints = {{1, 0, a, kAccelerate}, {-1, 0, a, kBrake}};
  return stages;
}

std::vector<double> Positions(const std::vector<ToppStage>& stages) {
  std::vector<double> s{0.0};
  for (std::size_t i = 0; i + 1 < stages.size(); ++i) s.push_back(s.back() + stages[i].delta);
  return s;
}

double Duration(const std::vector<ToppStage>& stages, const ToppResult& result) {
  return ToppTimes(Positions(stages), result).back();
}

// The profile is a motion of the discretised problem: at rest at both ends,
// x >= 0, x_{i+1} = x_i + 2 delta u_i, every half-plane and x_max met (1e-9
// relative to the terms), x_i within the controllable sets.
void ExpectAdmissible(const std::vector<ToppStage>& stages, const ToppResult& r) {
  ASSERT_TRUE(r.feasible);
  const std::size_t n = stages.size() - 1;
  ASSERT_EQ(r.x.size(), n + 1);
  ASSERT_EQ(r.u.size(), n);
  ASSERT_EQ(r.active.size(), n);
  EXPECT_EQ(r.x[0], 0.0);
  EXPECT_EQ(r.x[n], 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    SCOPED_TRACE("stage " + std::to_string(i));
    const double x = r.x[i], u = r.u[i];
    EXPECT_GE(x, 0.0);
    EXPECT_LE(x, stages[i].x_max * (1 + 1e-12));
    EXPECT_GE(x, r.k_min[i] - 1e-12 * r.k_max[i]);
    EXPECT_LE(x, r.k_max[i] * (1 + 1e-12));
    EXPECT_NEAR(r.x[i + 1], x + 2 * stages[i].delta * u, 1e-12 * (x + r.x[i + 1] + 1e-300));
    for (const HalfPlane& h : stages[i].constraints) {
      const double scale = std::abs(h.p * u) + std::abs(h.q * x) + std::abs(h.r);
      EXPECT_LE(h.p * u + h.q * x - h.r, 1e-9 * scale) << "limit " << h.limit_id;
    }
  }
}

TEST(ConvexPolygon, SquareClippedByADiagonalIsItsHalf) {
  const Polygon square = BoxPolygon(0, 1, 0, 1);
  EXPECT_EQ(SignedArea(square), 1.0);
  Polygon half;
  ClipByHalfPlane(square, 1, 1, 1, &half);  // x + y <= 1
  ASSERT_EQ(half.size(), 3u);
  EXPECT_EQ(half[0], Eigen::Vector2d(0, 0));
  EXPECT_EQ(half[1], Eigen::Vector2d(1, 0));
  EXPECT_EQ(half[2], Eigen::Vector2d(0, 1));
  EXPECT_EQ(SignedArea(half), 0.5);
  // x + y <= 1.5 cuts the corner (1, 1): a pentagon of area 1 - 1/8.
  Polygon cut;
  ClipByHalfPlane(square, 1, 1, 1.5, &cut);
  ASSERT_EQ(cut.size(), 5u);
  EXPECT_EQ(cut[2], Eigen::Vector2d(1, 0.5));
  EXPECT_EQ(cut[3], Eigen::Vector2d(0.5, 1));
  EXPECT_EQ(SignedArea(cut), 0.875);
  double lo = 0, hi = 0;
  ClipByHalfPlane(square, -2, 0, -0.5, &cut);  // x >= 0.25
  XRange(cut, &lo, &hi);
  EXPECT_EQ(lo, 0.25);
  EXPECT_EQ(hi, 1.0);
  EXPECT_EQ(SignedArea(cut), 0.75);
}

TEST(ConvexPolygon, EmptyAndDegenerateResults) {
  const Polygon square = BoxPolygon(0, 1, 0, 1);
  Polygon out{Eigen::Vector2d(9, 9)};
  ClipByHalfPlane(square, 1, 1, -0.5, &out);  // x + y <= -1/2: nothing
  EXPECT_TRUE(out.empty());
  Polygon still;
  ClipByHalfPlane(out, 1, 0, 1, &still);
  EXPECT_TRUE(still.empty());
  // A segment on a line y = m x + c, clipped by the line's equality as two
  // half-planes, survives although its vertices are only on the line to
  // rounding (without the slack, 26 of these 1000 were lost).
  std::mt19937 rng{52102};
  std::uniform_real_distribution<double> d(-3.0, 3.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const std::vector<double> r{d(rng), d(rng), d(rng), d(rng)};
    const double m = r[0], c = r[1];
    const Polygon segment{Eigen::Vector2d(r[2], m * r[2] + c), Eigen::Vector2d(r[3], m * r[3] + c)};
    Polygon below, line;
    ClipByHalfPlane(segment, m, -1, -c, &below);
    ClipByHalfPlane(below, -m, 1, c, &line);
    ASSERT_FALSE(line.empty()) << "trial " << trial;
    double lo = 0, hi = 0;
    XRange(line, &lo, &hi);
    EXPECT_EQ(lo, std::min(r[2], r[3]));
    EXPECT_EQ(hi, std::max(r[2], r[3]));
  }
  // A crossing far along a long edge is taken from its near end: accurate to
  // rounding of the small numbers (from the far end: 1e-7 off).
  Polygon tall;
  double lo = 0, hi = 0;
  ClipByHalfPlane(BoxPolygon(0, 3.1e9, 0, 0.987654), 1, -1, 1.3, &tall);  // x <= y + 1.3
  XRange(tall, &lo, &hi);
  EXPECT_NEAR(hi, 0.987654 + 1.3, 1e-15);
}

TEST(ToppRa, DoubleIntegratorIsBangBang) {
  const double length = 2.0, a = 3.0;
  const auto stages = DoubleIntegrator(2000, length, a);
  const ToppResult r = ToppRa(stages, kUBound);
  ExpectAdmissible(stages, r);
  EXPECT_NEAR(Duration(stages, r), 2 * std::sqrt(length / a), 1e-6 * 2 * std::sqrt(length / a));  // 3e-8 measured
  // Peak s'^2 = a L (half way, accelerating at a from rest).
  double peak = 0;
  for (double x : r.x) peak = std::max(peak, x);
  EXPECT_NEAR(peak, a * length, 2e-3 * a * length);
}

TEST(ToppRa, DoubleIntegratorWithARateLimitCruises) {
  const double length = 2.0, a = 3.0, v = 1.5;  // v^2 < a L: the rate limit binds
  for (bool as_half_plane : {false, true}) {
    auto stages = DoubleIntegrator(2000, length, a, as_half_plane ? kInf : v * v);
    if (as_half_plane) {
      for (ToppStage& stage : stages) stage.constraints.push_back({0, 1, v * v, kRateHalfPlane});
    }
    const ToppResult r = ToppRa(stages, kUBound);
    ExpectAdmissible(stages, r);
    const double expected = length / v + v / a;
    EXPECT_NEAR(Duration(stages, r), expected, 1e-6 * expected);  // 7e-8 measured
    // The cruise (s' = v, s'' = 0) reports the rate limit; ramps the others.
    const int rate_id = as_half_plane ? kRateHalfPlane : kRate;
    int cruising = 0;
    for (std::size_t i = 0; i < r.u.size(); ++i) {
      SCOPED_TRACE("segment " + std::to_string(i));
      if (r.x[i] == v * v && r.x[i + 1] == v * v) {
        ++cruising;
        EXPECT_EQ(r.active[i], rate_id);
      } else {
        EXPECT_TRUE(r.active[i] == kAccelerate || r.active[i] == kBrake || r.active[i] == rate_id) << r.active[i];
      }
    }
    // Ramps take v^2 / (2 a) each of the length.
    EXPECT_NEAR(cruising * stages[0].delta, length - v * v / a, 3 * stages[0].delta);
  }
}

// With 1999 segments (odd), the middle one has x_i = x_{i+1} (the switch):
// s'' = 0, no limit of its own is tight, and the braking limit ahead is
// inherited. Every other segment is at +a or -a.
TEST(ToppRa, ReportsTheActiveLimitOfEverySegment) {
  const auto stages = DoubleIntegrator(2000, 2.0, 3.0);
  const ToppResult r = ToppRa(stages, kUBound);
  ASSERT_TRUE(r.feasible);
  const int middle = 999;
  ASSERT_EQ(r.u.size(), 1999u);
  EXPECT_NEAR(r.u[middle], 0.0, 1e-9);
  for (int i = 0; i < 1999; ++i) {
    SCOPED_TRACE("segment " + std::to_string(i));
    if (i < middle) {
      EXPECT_NEAR(r.u[i], 3.0, 1e-9);
      EXPECT_EQ(r.active[i], kAccelerate);
    } else {
      if (i > middle) {
        EXPECT_NEAR(r.u[i], -3.0, 1e-9);
      }
      EXPECT_EQ(r.active[i], kBrake);
    }
  }
}

// Several limits within kToppTight of tight: the tightest is reported,
// wherever it is listed.
TEST(ToppRa, ReportsTheTightestOfSeveralLimits) {
  const double a = 3.0;
  auto stages = DoubleIntegrator(200, 2.0, a);
  for (ToppStage& stage : stages) {
    stage.constraints.insert(stage.constraints.begin(), {1, 0, a * (1 + 1e-9), 9});
    stage.constraints.push_back({1, 0, a * (1 + 2e-9), 8});
  }
  const ToppResult r = ToppRa(stages, kUBound);
  ExpectAdmissible(stages, r);
  EXPECT_EQ(r.active[0], kAccelerate);
  EXPECT_EQ(r.active[50], kAccelerate);
  EXPECT_EQ(r.active[150], kBrake);
}

// Only the u_bound box limits: it is the caller's numerical box, not a limit,
// so no segment reports one; the motion is still bang-bang at u_bound.
TEST(ToppRa, TheUBoundIsNotALimit) {
  const double length = 1.0, bound = 2.0;
  auto stages = UniformStages(101, length, kInf);
  const ToppResult r = ToppRa(stages, bound);
  ExpectAdmissible(stages, r);
  for (int id : r.active) EXPECT_EQ(id, -1);
  EXPECT_NEAR(Duration(stages, r), 2 * std::sqrt(length / bound), 1e-12);
}

// s'' + c s'^2 <= A accelerating (a drag), |s''| <= A braking. Accelerating
// from rest, dx/ds = 2 (A - c x): x = (A/c)(1 - exp(-2 c s)); braking to rest
// at L: x = 2 A (L - s); they meet at s*. Time: int ds / sqrt(x) =
// artanh(w*) / sqrt(A c) with w* = sqrt(1 - exp(-2 c s*)), plus
// sqrt(2 (L - s*) / A). The discretisation is explicit Euler in x: O(delta).
TEST(ToppRa, DragLikeLimitMatchesItsClosedForm) {
  const double length = 1.0, a = 1.0, c = 1.5;
  auto stages = DoubleIntegrator(2001, length, a);
  for (ToppStage& stage : stages) stage.constraints[0].q = c;
  const ToppResult r = ToppRa(stages, kUBound);
  ExpectAdmissible(stages, r);
  double lo = 0, hi = length;  // bisection for s*
  for (int k = 0; k < 200; ++k) {
    const double s = (lo + hi) / 2;
    ((a / c) * (1 - std::exp(-2 * c * s)) < 2 * a * (length - s) ? lo : hi) = s;
  }
  const double w = std::sqrt(1 - std::exp(-2 * c * lo));
  const double expected = std::atanh(w) / std::sqrt(a * c) + std::sqrt(2 * (length - lo) / a);
  EXPECT_NEAR(Duration(stages, r), expected, 5e-4 * expected);  // 1.6e-4 measured
  for (std::size_t i = 0; i < r.active.size(); ++i) EXPECT_NE(r.active[i], -1) << "segment " << i;
}

// Three "efforts" e_j = a_j(s) u + b_j(s) x + c_j(s) within [-1, 1], smooth in
// s with seeded random coefficients: every half-plane met at every stage, and
// a limit reported on every segment (the greedy profile is always against a
// limit of its own or one ahead).
TEST(ToppRa, ProfileMeetsEveryHalfPlane) {
  std::mt19937 rng{52101};
  std::uniform_real_distribution<double> phase(0.0, 6.283), weight(0.2, 0.8);
  for (int trial = 0; trial < 5; ++trial) {
    auto stages = UniformStages(400, 1.0, kInf);
    const std::vector<double> ph{phase(rng), phase(rng), phase(rng)};
    const std::vector<double> w{weight(rng), weight(rng), weight(rng)};
    for (std::size_t i = 0; i < stages.size(); ++i) {
      const double s = i * stages[0].delta;
      for (int j = 0; j < 3; ++j) {
        const double aj = 1 + 0.5 * std::sin(3 * s + ph[j]), bj = w[j] * std::cos(5 * s + ph[j]);
        const double cj = 0.4 * w[j] * std::sin(2 * s - ph[j]);
        stages[i].constraints.push_back({aj, bj, 1 - cj, 2 * j});
        stages[i].constraints.push_back({-aj, -bj, 1 + cj, 2 * j + 1});
      }
    }
    SCOPED_TRACE("trial " + std::to_string(trial));
    const ToppResult r = ToppRa(stages, kUBound);
    ExpectAdmissible(stages, r);
    for (std::size_t i = 0; i < r.active.size(); ++i) EXPECT_NE(r.active[i], -1) << "segment " << i;
  }
}

TEST(ToppRa, ReportsTheStageWhoseSetIsEmpty) {
  const double length = 2.0, a = 3.0;
  // Stage 1400 demands more rate than braking at a can take back to rest
  // before the end (2 a (L - s) at most; accelerating from rest reaches
  // 2 a s, more): K_1400 is empty.
  auto stages = DoubleIntegrator(2000, length, a);
  const double s1400 = 1400 * stages[0].delta;
  stages[1400].constraints.push_back({0, -1, -1.01 * 2 * a * (length - s1400), 7});
  ToppResult r = ToppRa(stages, kUBound);
  EXPECT_FALSE(r.feasible);
  EXPECT_EQ(r.failed_stage, 1400);
  // A rate demanded at stage 0: rest is not in K_0.
  stages = DoubleIntegrator(2000, length, a);
  stages[0].constraints.push_back({0, -1, -0.1, 7});
  r = ToppRa(stages, kUBound);
  EXPECT_FALSE(r.feasible);
  EXPECT_EQ(r.failed_stage, 0);
  // The last stage cannot hold still (a static effort beyond its limit).
  stages = DoubleIntegrator(2000, length, a);
  stages.back().constraints.push_back({0, 0, -0.5, 7});
  r = ToppRa(stages, kUBound);
  EXPECT_FALSE(r.feasible);
  EXPECT_EQ(r.failed_stage, 1999);
  // Just within: feasible.
  stages = DoubleIntegrator(2000, length, a);
  stages[1400].constraints.push_back({0, -1, -0.99 * 2 * a * (length - s1400), 7});
  r = ToppRa(stages, kUBound);
  ExpectAdmissible(stages, r);
  EXPECT_GE(r.x[1400], 0.99 * 2 * a * (length - s1400));
}

TEST(ToppRa, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ToppRa(DoubleIntegrator(2, 1.0, 1.0), kUBound), std::invalid_argument);
  EXPECT_THROW(ToppRa(DoubleIntegrator(3, 1.0, 1.0), 0.0), std::invalid_argument);
  EXPECT_THROW(ToppRa(DoubleIntegrator(3, 1.0, 1.0), kInf), std::invalid_argument);
  auto stages = DoubleIntegrator(3, 1.0, 1.0);
  stages[1].delta = 0;
  EXPECT_THROW(ToppRa(stages, kUBound), std::invalid_argument);
  stages = DoubleIntegrator(3, 1.0, 1.0);
  stages[2].delta = nan;  // unused on the last stage
  EXPECT_NO_THROW(ToppRa(stages, kUBound));
  stages[1].x_max = nan;
  EXPECT_THROW(ToppRa(stages, kUBound), std::invalid_argument);
  stages = DoubleIntegrator(3, 1.0, 1.0);
  stages[0].constraints[1].r = kInf;
  EXPECT_THROW(ToppRa(stages, kUBound), std::invalid_argument);

  stages = DoubleIntegrator(3, 1.0, 1.0);
  const ToppResult r = ToppRa(stages, kUBound);
  EXPECT_THROW(ToppTimes({0.0, 0.5}, r), std::invalid_argument);
  EXPECT_THROW(ToppTimes({0.0, 0.5, 0.5}, r), std::invalid_argument);
  ToppResult stuck = r;
  stuck.x[1] = 0;
  EXPECT_THROW(ToppTimes({0.0, 0.5, 1.0}, stuck), std::invalid_argument);
  stuck.feasible = false;
  EXPECT_THROW(ToppTimes({0.0, 0.5, 1.0}, stuck), std::invalid_argument);
  // Two segments: accelerate, brake, T = 2 sqrt(L / a) exactly.
  EXPECT_NEAR(ToppTimes({0.0, 0.5, 1.0}, r).back(), 2.0, 1e-15);
}

}  // namespace topp_ra_test
}  // namespace internal
}  // namespace ccma
