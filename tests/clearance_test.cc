// Clearance (model_format.md, "Collision geometry and obstacles"): the
// closed-form distances of collision/ against geometry and against FCL, the
// gradients against central differences at seeded states (and a wrong
// gradient caught), the broad phase against brute force, and the loader.
#include <cmath>
#include <fstream>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <fcl/narrowphase/distance.h>
#include <gtest/gtest.h>

#include "collision/clearance.h"
#include "collision/collision_model.h"
#include "formats/model_loader.h"
#include "formats/obstacles_file.h"
#include "tests/tool_run.h"

namespace ccma {
namespace clearance_test {

PlacedShape Disc(double x, double y, double r, double z0, double z1) {
  PlacedShape s;
  s.center = {x, y};
  s.radius = r;
  s.z_min = z0;
  s.z_max = z1;
  UpdateBoundingBox(&s);
  return s;
}

PlacedShape Rect(double x, double y, double z, double sx, double sy, double sz, double yaw) {
  PlacedShape s;
  s.footprint = Footprint::kRectangle;
  s.center = {x, y};
  s.half_size = {0.5 * sx, 0.5 * sy};
  s.cos_yaw = std::cos(yaw);
  s.sin_yaw = std::sin(yaw);
  s.z_min = z - 0.5 * sz;
  s.z_max = z + 0.5 * sz;
  UpdateBoundingBox(&s);
  return s;
}

PlacedShape Capsule(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r) {
  PlacedShape s;
  s.kind = ShapeKind::kCapsule;
  s.a_W = a;
  s.b_W = b;
  s.radius = r;
  UpdateBoundingBox(&s);
  return s;
}

TEST(ShapeDistance, ClosedForms) {
  // Two bases 1 m apart (radii 0.3, 0.2), and overlapping by 0.1 m.
  EXPECT_NEAR(Distance(Disc(0, 0, 0.3, 0, 0.2), Disc(1, 0, 0.2, 0, 0.2)).distance, 0.5, 1e-15);
  EXPECT_NEAR(Distance(Disc(0, 0, 0.3, 0, 0.2), Disc(0.4, 0, 0.2, 0, 0.2)).distance, -0.1, 1e-15);
  // A base against a 2 x 1 box: along x, turned by 90 degrees, at a corner.
  EXPECT_NEAR(Distance(Disc(2, 0, 0.3, 0, 0.2), Rect(0, 0, 0.5, 2, 1, 1, 0)).distance, 0.7, 1e-15);
  EXPECT_NEAR(Distance(Disc(2, 0, 0.3, 0, 0.2), Rect(0, 0, 0.5, 2, 1, 1, M_PI / 2)).distance, 1.2, 1e-15);
  EXPECT_NEAR(Distance(Disc(2, 2, 0.3, 0, 0.2), Rect(0, 0, 0.5, 2, 1, 1, 0)).distance,
              std::hypot(1.0, 1.5) - 0.3, 1e-15);
  // The same box, order reversed: the same distance, the normal reversed.
  const ShapeDistance ab = Distance(Disc(2, 0, 0.3, 0, 0.2), Rect(0, 0, 0.5, 2, 1, 1, 0));
  const ShapeDistance ba = Distance(Rect(0, 0, 0.5, 2, 1, 1, 0), Disc(2, 0, 0.3, 0, 0.2));
  EXPECT_NEAR(ab.distance, ba.distance, 1e-15);
  EXPECT_NEAR((ab.n + ba.n).norm(), 0, 1e-15);
  EXPECT_NEAR(ab.n.x(), -1, 1e-15);  // from the base toward the box
  // A box floating 0.3 m above a base's top (0.2): straight above, and aside.
  EXPECT_NEAR(Distance(Disc(0, 0, 0.3, 0, 0.2), Rect(0, 0, 1.0, 1, 1, 1, 0)).distance, 0.3, 1e-15);
  EXPECT_NEAR(Distance(Disc(1.2, 0, 0.3, 0, 0.2), Rect(0, 0, 1.0, 1, 1, 1, 0)).distance, std::hypot(0.4, 0.3), 1e-15);
  // Capsules: parallel 1 m apart, skew 0.5 m apart, overlapping.
  EXPECT_NEAR(Distance(Capsule({0, 0, 1}, {1, 0, 1}, 0.1), Capsule({0, 1, 1}, {1, 1, 1}, 0.1)).distance, 0.8, 1e-15);
  EXPECT_NEAR(Distance(Capsule({-1, 0, 0}, {1, 0, 0}, 0.1), Capsule({0, -1, 0.5}, {0, 1, 0.5}, 0.05)).distance, 0.35,
              1e-15);
  EXPECT_NEAR(Distance(Capsule({-1, 0, 0}, {1, 0, 0}, 0.1), Capsule({0, -1, 0.1}, {0, 1, 0.1}, 0.05)).distance, -0.05,
              1e-15);
  // A capsule beside a pillar (radius 0.2, 2 m high), and passing over it.
  const PlacedShape pillar = Disc(0, 0, 0.2, 0, 2);
  EXPECT_NEAR(Distance(Capsule({-1, 0.5, 1}, {1, 0.5, 1}, 0.05), pillar).distance, 0.25, 1e-12);
  EXPECT_NEAR(Distance(pillar, Capsule({-1, 0, 2.5}, {1, 0, 2.5}, 0.05)).distance, 0.45, 1e-12);
  // Its end 0.3 m from the pillar's rim at the top corner.
  EXPECT_NEAR(Distance(Capsule({0.2 + 0.3, 0, 2 + 0.4}, {2, 0, 2 + 0.4}, 0.1), pillar).distance, 0.4, 1e-12);
  // Through the pillar: the depth of the axis inside, plus the radius.
  EXPECT_NEAR(Distance(Capsule({-1, 0.1, 1}, {1, 0.1, 1}, 0.05), pillar).distance, -(0.1 + 0.05), 1e-12);
}

// ---- Against FCL (an independent GJK; ccma's forms are exact) -------------

std::shared_ptr<fcl::CollisionObjectd> ToFcl(const PlacedShape& s) {
  fcl::Transform3d X = fcl::Transform3d::Identity();
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  if (s.kind == ShapeKind::kCapsule) {
    const Eigen::Vector3d axis = s.b_W - s.a_W;
    geometry = std::make_shared<fcl::Capsuled>(s.radius, axis.norm());
    X.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
    X.translation() = 0.5 * (s.a_W + s.b_W);
  } else {
    const double h = s.z_max - s.z_min;
    if (s.footprint == Footprint::kDisc) {
      geometry = std::make_shared<fcl::Cylinderd>(s.radius, h);
    } else {
      geometry = std::make_shared<fcl::Boxd>(2 * s.half_size.x(), 2 * s.half_size.y(), h);
      X.linear() = Eigen::AngleAxisd(std::atan2(s.sin_yaw, s.cos_yaw), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    }
    X.translation() << s.center, 0.5 * (s.z_min + s.z_max);
  }
  return std::make_shared<fcl::CollisionObjectd>(geometry, X);
}

double FclDistance(const PlacedShape& a, const PlacedShape& b) {
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.distance_tolerance = 1e-12;
  fcl::DistanceResultd result;
  fcl::distance(ToFcl(a).get(), ToFcl(b).get(), request, result);
  return result.min_distance;
}

struct RandomShapes {
  std::mt19937 rng{20261201};
  double U(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  PlacedShape Base() { return Disc(U(-2, 2), U(-2, 2), U(0.1, 0.5), 0, U(0.1, 0.5)); }
  PlacedShape Pillar() { return Disc(U(-2, 2), U(-2, 2), U(0.1, 0.5), 0, U(0.5, 3)); }
  PlacedShape Box() { return Rect(U(-2, 2), U(-2, 2), U(0, 2), U(0.2, 1.5), U(0.2, 1.5), U(0.2, 1.5), U(-3, 3)); }
  PlacedShape Link() {
    const Eigen::Vector3d a(U(-2, 2), U(-2, 2), U(0, 2.5));
    return Capsule(a, a + Eigen::Vector3d(U(-1, 1), U(-1, 1), U(-1, 1)), U(0.02, 0.2));
  }
};

TEST(ShapeDistance, MatchesFclOnSeparatedPairs) {
  RandomShapes r;
  struct Kind {
    const char* name;
    std::function<PlacedShape()> a, b;
  };
  const std::vector<Kind> kinds = {
      {"base-base", [&] { return r.Base(); }, [&] { return r.Base(); }},
      {"base-pillar", [&] { return r.Base(); }, [&] { return r.Pillar(); }},
      {"base-box", [&] { return r.Base(); }, [&] { return r.Box(); }},
      {"link-link", [&] { return r.Link(); }, [&] { return r.Link(); }},
      {"link-pillar", [&] { return r.Link(); }, [&] { return r.Pillar(); }},
      {"link-box", [&] { return r.Link(); }, [&] { return r.Box(); }},
      {"link-base", [&] { return r.Link(); }, [&] { return r.Base(); }},
  };
  for (const Kind& kind : kinds) {
    int compared = 0;
    double worst = 0;
    for (int i = 0; i < 300; ++i) {
      const PlacedShape a = kind.a(), b = kind.b();
      const double d = Distance(a, b).distance;
      if (d < 1e-3) continue;  // FCL's distance is for separated shapes
      worst = std::max(worst, std::abs(d - FclDistance(a, b)));
      ++compared;
    }
    EXPECT_GT(compared, 100) << kind.name;
    EXPECT_LT(worst, 1e-6) << kind.name;  // FCL's GJK converges to about 1e-7 m
  }
}

// ---- Gradients over the state ---------------------------------------------

std::string ModelText(const std::string& collision_extra = "") {
  std::ifstream in(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text +
         "collision:\n  margin: 0.05\n  base_radius: 0.25\n" + collision_extra + "  links:\n"
         "    - {body: link0, from: [0, 0.583012702, 0.35], to: [0, 0.15, 0.6], radius: 0.03}\n"
         "    - {body: link1, from: [-0.504903811, -0.291506351, 0.35], to: [-0.129903811, -0.075, 0.6], radius: 0.03}\n"
         "    - {body: link2, from: [0.504903811, -0.291506351, 0.35], to: [0.129903811, -0.075, 0.6], radius: 0.03}\n"
         "    - {body: ee, from: [-0.1, 0, 0.6], to: [0.1, 0, 0.6], radius: 0.05}\n"
         "    - {body: post0, from: [0, 0.583012702, 0.1], to: [0, 0.583012702, 0.35], radius: 0.04}\n"
         "obstacles:\n"
         "  - {name: pillar, cylinder: {center: [0.6, 0.4], radius: 0.15, height: 1.0}}\n"
         "  - {name: crate, box: {center: [-0.5, 0.5, 0.3], size: [0.4, 0.3, 0.6], yaw: 0.4}}\n"
         "  - {name: shelf, box: {center: [0.0, -0.7, 0.45], size: [1.2, 0.2, 0.1], yaw: 0.1}}\n";
}

// Home moved by a seeded normal tangent step of deviation `sigma` per coordinate.
State RandomState(const Model& model, std::mt19937* rng, double sigma) {
  std::normal_distribution<double> normal(0.0, sigma);
  State s = State::Home(model);
  Eigen::VectorXd ds(s.tangent_size());
  for (int i = 0; i < ds.size(); ++i) ds[i] = normal(*rng);
  s.Plus(ds);
  return s;
}

// Largest |analytic - central difference| over the pairs near each other at
// seeded random states (pairs at a tie, where one-sided differences
// disagree, skipped). `tamper` may spoil the analytic gradient.
struct GradientCheck {
  double worst = 0;
  int compared = 0;
};
GradientCheck CheckGradients(const std::function<void(Eigen::Matrix<double, 1, 6>*)>& tamper) {
  const Model model = LoadModelFromString(ModelText(), "clearance.yaml");
  const CollisionModel collision(model);
  std::mt19937 rng(7);
  GradientCheck out;
  std::vector<PlacedShape> shapes;
  for (int trial = 0; trial < 20; ++trial) {
    const State s = RandomState(model, &rng, 0.15);
    collision.PlaceShapes(s, &shapes);
    for (const PairClearance& pair : NearClearances(collision, shapes, 10.0)) {
      // A capsule inside a prism: its deepest point sits where two faces'
      // depths tie (the minimum of a maximum), a kink: no gradient there.
      if (pair.distance.distance < 0 && shapes[pair.a].kind != shapes[pair.b].kind) continue;
      Eigen::Matrix<double, 1, 6> g[2];
      ClearanceGradient(collision, s, pair, &g[0], &g[1]);
      tamper(&g[1]);
      const int bodies[2] = {collision.BodyOf(pair.a), collision.BodyOf(pair.b)};
      for (int k = 0; k < 2; ++k) {
        if (bodies[k] == kWorld) continue;
        for (int c = 0; c < 6; ++c) {
          auto at = [&](double h) {
            State moved = s;
            Eigen::VectorXd step = Eigen::VectorXd::Zero(s.tangent_size());
            step[6 * bodies[k] + c] = h;
            moved.Plus(step);
            std::vector<PlacedShape> placed;
            collision.PlaceShapes(moved, &placed);
            return Distance(placed[pair.a], placed[pair.b]).distance;
          };
          const double h = 1e-6, d0 = pair.distance.distance;
          const double forward = (at(h) - d0) / h, backward = (d0 - at(-h)) / h;
          if (std::abs(forward - backward) > 1e-4) continue;  // a tie: not differentiable here
          const double err = std::abs(g[k][c] - 0.5 * (forward + backward));
          out.worst = std::max(out.worst, err);
          ++out.compared;
        }
      }
    }
  }
  return out;
}

TEST(ClearanceGradient, MatchesCentralDifferences) {
  const GradientCheck check = CheckGradients([](Eigen::Matrix<double, 1, 6>*) {});
  EXPECT_GT(check.compared, 500);
  EXPECT_LT(check.worst, 1e-7);
}

TEST(ClearanceGradient, CheckerCatchesAWrongGradient) {
  // The rotation part's sign flipped (the lever arm taken the wrong way).
  const GradientCheck check = CheckGradients([](Eigen::Matrix<double, 1, 6>* g) { g->head<3>() *= -1; });
  EXPECT_GT(check.worst, 1e-3);
}

// ---- Broad phase ----------------------------------------------------------

TEST(BroadPhase, FindsEveryPairWithinTheThreshold) {
  const Model model = LoadModelFromString(ModelText(), "clearance.yaml");
  const CollisionModel collision(model);
  std::mt19937 rng(11);
  std::vector<PlacedShape> shapes;
  for (int trial = 0; trial < 20; ++trial) {
    const State s = RandomState(model, &rng, 0.3);
    collision.PlaceShapes(s, &shapes);
    for (double threshold : {0.0, 0.05, 0.3}) {
      std::vector<std::pair<int, int>> near;
      std::vector<int> order;
      NearPairs(collision, shapes, threshold, &near, &order);
      const std::set<std::pair<int, int>> found(near.begin(), near.end());
      EXPECT_EQ(found.size(), near.size());  // no pair twice
      for (int i = 0; i < collision.num_shapes(); ++i) {
        for (int j = i + 1; j < collision.num_shapes(); ++j) {
          if (!collision.Checked(i, j)) {
            EXPECT_EQ(found.count({i, j}), 0u);
          } else if (Distance(shapes[i], shapes[j]).distance <= threshold) {
            EXPECT_EQ(found.count({i, j}), 1u) << i << " " << j;
          }
        }
      }
    }
  }
}

TEST(CollisionModel, SkipsJointedBodiesIgnoredPairsAndObstaclePairs) {
  const Model model = LoadModelFromString(ModelText(), "clearance.yaml");
  const CollisionModel collision(model);
  // Shapes: 3 bases, 5 capsules, 3 obstacles.
  ASSERT_EQ(collision.num_shapes(), 11);
  EXPECT_FALSE(collision.Checked(8, 9));   // pillar-crate
  EXPECT_FALSE(collision.Checked(3, 6));   // link0-ee share a joint
  EXPECT_FALSE(collision.Checked(0, 7));   // base0-post0 share a joint
  EXPECT_TRUE(collision.Checked(3, 4));    // link0-link1
  EXPECT_TRUE(collision.Checked(0, 1));    // base0-base1
  EXPECT_TRUE(collision.Checked(6, 8));    // ee-pillar
  const Model ignoring = LoadModelFromString(ModelText("  ignore: [[link0, link1], [pillar, ee]]\n"), "c.yaml");
  const CollisionModel fewer(ignoring);
  EXPECT_FALSE(fewer.Checked(3, 4));
  EXPECT_FALSE(fewer.Checked(8, 6));
  EXPECT_TRUE(fewer.Checked(3, 5));
}

// ---- The loader -------------------------------------------------------------

TEST(CollisionLoader, ReadsTheContractExample) {
  const Model model = LoadModelFromString(ModelText(), "clearance.yaml");
  const CollisionGeometry& g = model.collision;
  EXPECT_TRUE(g.enabled);
  EXPECT_DOUBLE_EQ(g.margin, 0.05);
  EXPECT_EQ(g.base_radii, std::vector<double>({0.25, 0.25, 0.25}));
  EXPECT_DOUBLE_EQ(g.base_height, 0.2);
  ASSERT_EQ(g.links.size(), 5u);
  ASSERT_EQ(g.obstacles.size(), 3u);
  EXPECT_EQ(g.obstacles[1].name, "crate");
  EXPECT_DOUBLE_EQ(g.obstacles[1].z_min, 0.0);
  EXPECT_DOUBLE_EQ(g.obstacles[1].z_max, 0.6);
  // Capsule ends are world coordinates at home: placed at home they are back.
  const CollisionModel collision(model);
  std::vector<PlacedShape> shapes;
  collision.PlaceShapes(State::Home(model), &shapes);
  EXPECT_NEAR((shapes[3].b_W - Eigen::Vector3d(0, 0.15, 0.6)).norm(), 0, 1e-12);
  // Without the keys: disabled, defaults.
  std::ifstream in(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const std::string plain((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::string> warnings;
  const Model without = LoadModelFromString(plain, "plain.yaml", &warnings);
  EXPECT_FALSE(without.collision.enabled);
  EXPECT_DOUBLE_EQ(without.collision.margin, 0.02);
  EXPECT_TRUE(warnings.empty());
  // A base's own radius.
  std::string own = plain;
  own.replace(own.find("pose: [0, 0.583012702"), 0, "radius: 0.4, ");
  EXPECT_EQ(LoadModelFromString(own + "obstacles: []\n", "own.yaml").collision.base_radii,
            std::vector<double>({0.4, 0.3, 0.3}));
}

void ExpectRejected(const std::string& extra, const std::string& message) {
  std::ifstream in(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const std::string plain((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    LoadModelFromString(plain + extra, "bad.yaml");
    ADD_FAILURE() << "accepted: " << extra;
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("bad.yaml:", 0), 0u) << e.what();
  }
}

TEST(CollisionLoader, RejectsMalformedShapesNamingFileLineAndKey) {
  ExpectRejected("collision: {margin: -0.1}\n", "collision.margin: must not be negative");
  ExpectRejected("collision: {base_radius: 0}\n", "collision.base_radius: must be positive");
  ExpectRejected("collision: {links: [{body: nobody, from: [0,0,0], to: [1,0,0], radius: 0.1}]}\n",
                 "collision.links[0].body: unknown body 'nobody'");
  ExpectRejected("collision: {links: [{body: ee, from: [0,0,.nan], to: [1,0,0], radius: 0.1}]}\n",
                 "collision.links[0].from[2]");
  ExpectRejected("collision: {links: [{body: ee, from: [0,0,0], to: [1,0,0], radius: -1}]}\n",
                 "collision.links[0].radius: must be positive");
  ExpectRejected("collision: {ignore: [[ee, ghost]]}\n", "collision.ignore[0][1]: unknown body, base or obstacle");
  ExpectRejected("obstacles: [{name: p, cylinder: {center: [0, 0], radius: 0, height: 1}}]\n",
                 "obstacles[0].cylinder.radius: must be positive");
  ExpectRejected("obstacles: [{name: p, cylinder: {center: [0, 0, 0], radius: 1, height: 1}}]\n",
                 "obstacles[0].cylinder.center: must be a list of 2 numbers");
  ExpectRejected("obstacles: [{name: p, box: {center: [0, 0, 0], size: [1, 0, 1]}}]\n",
                 "obstacles[0].box.size: every side must be positive");
  ExpectRejected("obstacles: [{name: p, box: {center: [0, 0, 0], size: [1, 1, 1]}, "
                 "cylinder: {center: [0, 0], radius: 1, height: 1}}]\n",
                 "obstacles[0]: give exactly one of cylinder: or box:");
  ExpectRejected("obstacles: [{name: base0, cylinder: {center: [0, 0], radius: 1, height: 1}}]\n",
                 "obstacles[0].name: the name 'base0' is already used");
  ExpectRejected("obstacles: [{name: p, box: {center: [0, 0, 0], size: [1, 1, 1]}}, "
                 "{name: p, box: {center: [0, 0, 0], size: [1, 1, 1]}}]\n",
                 "obstacles[1].name: the name 'p' is already used");
  ExpectRejected("obstacles: [{name: p, box: {center: [0, 0, 1e300], size: [1, 1, 1]}}]\n",
                 "obstacles[0].box.center[2]");
}

TEST(ObstaclesFile, AddsObstaclesAndRejectsOtherKeys) {
  const std::string dir = ccma::testing::TestDir();
  Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  ASSERT_FALSE(model.collision.enabled);
  {
    std::ofstream(dir + "/room.yaml") << "obstacles:\n  - {name: pillar, cylinder: {center: [1, 0], radius: 0.2, height: 2}}\n";
  }
  AddObstaclesFromFile(dir + "/room.yaml", &model);
  EXPECT_TRUE(model.collision.enabled);
  ASSERT_EQ(model.collision.obstacles.size(), 1u);
  EXPECT_EQ(model.collision.obstacles[0].name, "pillar");
  // Home: base2 at (0.505, -0.292), radius 0.3; the pillar at (1, 0), 0.2.
  const ClearanceSummary c = MinimumClearance(CollisionModel(model), State::Home(model));
  ASSERT_TRUE(c.any);
  EXPECT_NEAR(c.min, std::hypot(1 - 0.504903811, 0.291506351) - 0.5, 1e-9);
  EXPECT_EQ(c.a, "base2");
  EXPECT_EQ(c.b, "pillar");
  // The same name again, and a file with another key.
  EXPECT_THROW(AddObstaclesFromFile(dir + "/room.yaml", &model), ModelError);
  { std::ofstream(dir + "/bad.yaml") << "obstacles: []\nbodies: []\n"; }
  try {
    AddObstaclesFromFile(dir + "/bad.yaml", &model);
  } catch (const ModelError& e) {
    // An unknown key without a near match is a warning, not an error:
    ADD_FAILURE() << e.what();
  }
  EXPECT_THROW(AddObstaclesFromFile(dir + "/missing.yaml", &model), ModelError);
  { std::ofstream(dir + "/list.yaml") << "- {name: q}\n"; }
  EXPECT_THROW(AddObstaclesFromFile(dir + "/list.yaml", &model), ModelError);
}

}  // namespace
}  // namespace ccma
