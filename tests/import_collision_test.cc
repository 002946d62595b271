// `ccma import --collision_radius` (analyses/internal/import_collision.h):
// every link of an imported robot gets capsules along the shortest tree of
// its joint points, the model is clear of itself at home (pairs that touch by
// design are ignored, and really touch), the capsules survive the model file,
// and an obstacle is measured against them in closed form. Also the model
// writer's collision section on a bundled model with bases and obstacles.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analyses/robot_import.h"
#include "collision/clearance.h"
#include "collision/collision_model.h"
#include "formats/model_loader.h"
#include "formats/model_writer.h"
#include "formats/urdf_reader.h"

namespace ccma {
namespace import_collision_test {

const std::string kRobots = std::string(CCMA_MODELS_DIR) + "/robots/example-parallel-robots/";
constexpr double kRadius = 0.02;

ImportedRobot Import(const std::string& folder, const std::string& end_effector, double radius) {
  ImportOptions options;
  options.end_effector_link = end_effector;
  options.collision_radius = radius;
  return ImportRobot(ReadUrdf(kRobots + folder + "/robot.urdf", kRobots + folder + "/robot.yaml"), options);
}

double SegmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double t = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

struct Case {
  std::string folder, end_effector;
};
class ImportCollision : public ::testing::TestWithParam<Case> {};
INSTANTIATE_TEST_SUITE_P(Robots, ImportCollision,
                         ::testing::Values(Case{"5bar_linkage", "effector"}, Case{"robot_delta", "eff"},
                                           Case{"cassie_like", "foot"}, Case{"5bar_linkage_iso3d", "effector"},
                                           Case{"battobot_6d", "foot_left"}));

// Every joint point of a body (and the end-effector point) lies on one of its
// capsules, a body with k distinct points has max(1, k - 1) capsules, each of
// the given radius; the model is clear of itself at home by at least the
// margin; each ignored pair really is closer than the margin without the
// ignore list; the file holds the same capsules.
TEST_P(ImportCollision, CapsulesJoinEveryJointPointAndTheModelIsClearAtHome) {
  const ImportedRobot robot = Import(GetParam().folder, GetParam().end_effector, kRadius);
  const Model& m = robot.model;
  ASSERT_TRUE(m.collision.enabled);
  EXPECT_EQ(static_cast<int>(m.collision.links.size()), robot.collision_capsules);
  EXPECT_EQ(static_cast<int>(m.collision.ignore.size()), robot.collision_ignored_pairs);
  for (int b = 0; b < m.num_bodies(); ++b) {
    std::vector<Eigen::Vector3d> points;
    for (const Joint& joint : m.joints) {
      if (joint.body_a == b) points.push_back(joint.p_A);
      if (joint.body_b == b) points.push_back(joint.p_B);
    }
    if (m.end_effector.body == b) points.push_back(m.end_effector.p_B);
    std::vector<Eigen::Vector3d> distinct;
    for (const Eigen::Vector3d& p : points) {
      if (std::none_of(distinct.begin(), distinct.end(), [&](const Eigen::Vector3d& q) { return (p - q).norm() < 1e-9; }))
        distinct.push_back(p);
    }
    int capsules = 0;
    for (const CollisionCapsule& c : m.collision.links) capsules += c.body == b ? 1 : 0;
    EXPECT_EQ(capsules, std::max<int>(1, static_cast<int>(distinct.size()) - 1)) << m.bodies[b].name;
    for (const Eigen::Vector3d& p : distinct) {
      double nearest = 1e9;
      for (const CollisionCapsule& c : m.collision.links) {
        if (c.body == b) nearest = std::min(nearest, SegmentDistance(p, c.a_B, c.b_B));
      }
      EXPECT_LT(nearest, 1e-9) << m.bodies[b].name;
    }
  }
  for (const CollisionCapsule& c : m.collision.links) EXPECT_EQ(c.radius, kRadius);
  const ClearanceSummary home = MinimumClearance(CollisionModel(m), State::Home(m));
  ASSERT_TRUE(home.any);
  EXPECT_GE(home.min, m.collision.margin) << home.a << " " << home.b;
  Model unignored = m;
  unignored.collision.ignore.clear();
  const CollisionModel all(unignored);
  std::vector<PlacedShape> shapes;
  all.PlaceShapes(State::Home(unignored), &shapes);
  for (const auto& pair : m.collision.ignore) {
    double closest = 1e9;
    for (int i = 0; i < all.num_shapes(); ++i) {
      for (int j = i + 1; j < all.num_shapes(); ++j) {
        const bool named = (all.Name(i) == pair.first && all.Name(j) == pair.second) ||
                           (all.Name(i) == pair.second && all.Name(j) == pair.first);
        if (named) closest = std::min(closest, Distance(shapes[i], shapes[j]).distance);
      }
    }
    EXPECT_LT(closest, m.collision.margin) << pair.first << " " << pair.second;
  }
  const Model reread = LoadModelFromString(robot.yaml, "reread");
  ASSERT_EQ(reread.collision.links.size(), m.collision.links.size());
  for (std::size_t i = 0; i < m.collision.links.size(); ++i) {
    EXPECT_EQ(reread.collision.links[i].body, m.collision.links[i].body);
    EXPECT_LT((reread.collision.links[i].a_B - m.collision.links[i].a_B).norm(), 1e-12);
    EXPECT_LT((reread.collision.links[i].b_B - m.collision.links[i].b_B).norm(), 1e-12);
  }
  EXPECT_EQ(reread.collision.ignore, m.collision.ignore);
}

// Without the option there is no collision geometry (as before).
TEST(ImportCollisionOff, NoRadiusNoCollisionSection) {
  const ImportedRobot robot = Import("5bar_linkage", "effector", 0);
  EXPECT_FALSE(robot.model.collision.enabled);
  EXPECT_TRUE(robot.model.collision.links.empty());
  EXPECT_EQ(robot.yaml.find("collision:"), std::string::npos);
}

// The five-bar's effector point is its lowest point (the end rod's capsule
// ends there): a wide box whose top is 0.05 m below it is at clearance
// 0.05 - radius from the mechanism (closer than any pair of its links).
TEST(ImportCollisionFiveBar, ObstacleUnderTheEffectorIsMeasuredInClosedForm) {
  ImportedRobot robot = Import("5bar_linkage", "effector", kRadius);
  Model& m = robot.model;
  const Eigen::Vector3d p = m.end_effector.p_W_home;
  Obstacle ledge;
  ledge.name = "ledge";
  ledge.shape = ObstacleShape::kBox;
  ledge.size = Eigen::Vector3d(1.0, 1.0, 0.05);
  ledge.center = Eigen::Vector3d(p.x(), p.y(), p.z() - 0.05 - 0.025);
  ledge.z_min = ledge.center.z() - 0.025;
  ledge.z_max = ledge.center.z() + 0.025;
  m.collision.obstacles.push_back(ledge);
  const ClearanceSummary s = MinimumClearance(CollisionModel(m), State::Home(m));
  EXPECT_NEAR(s.min, 0.05 - kRadius, 1e-12);
  EXPECT_TRUE(s.a == "ledge" || s.b == "ledge");
}

// The writer's collision section: bundled models with bases and a pillar,
// given a base's own radius, a capsule, an ignored pair and a turned box,
// read back with the same geometry.
TEST(ModelWriterCollision, BundledObstacleModelReadsBackTheSame) {
  for (const char* file : {"/../examples/obstacles/pillar_detour.yaml", "/../examples/obstacles/six_agents_pillar.yaml"}) {
    const Model m = LoadModel(std::string(CCMA_MODELS_DIR) + file);
    ASSERT_TRUE(m.collision.enabled) << file;
    Model edited = m;
    edited.collision.base_radii[0] = 0.123;  // a base's own radius
    Obstacle crate;
    crate.name = "crate";
    crate.shape = ObstacleShape::kBox;
    crate.center = Eigen::Vector3d(3, 1, 0.4);
    crate.size = Eigen::Vector3d(0.5, 0.2, 0.3);
    crate.yaw = 0.3;
    crate.z_min = 0.25, crate.z_max = 0.55;
    edited.collision.obstacles.push_back(crate);
    CollisionCapsule arm;  // a capsule on the last body, in its frame
    arm.body = edited.num_bodies() - 1;
    arm.a_B = Eigen::Vector3d(0.1, -0.2, 0.3);
    arm.b_B = Eigen::Vector3d(-0.05, 0.25, 0.1);
    arm.radius = 0.04;
    edited.collision.links.push_back(arm);
    edited.collision.ignore.emplace_back(edited.bodies[0].name, "pillar");
    const Model r = LoadModelFromString(WriteModelYaml(edited), "written");
    const CollisionGeometry &a = edited.collision, &b = r.collision;
    ASSERT_TRUE(b.enabled);
    EXPECT_EQ(b.margin, a.margin);
    EXPECT_EQ(b.base_radius, a.base_radius);
    EXPECT_EQ(b.base_height, a.base_height);
    EXPECT_EQ(b.base_radii, a.base_radii);
    EXPECT_EQ(b.ignore, a.ignore);
    ASSERT_EQ(b.links.size(), a.links.size());
    for (std::size_t i = 0; i < a.links.size(); ++i) {
      EXPECT_LT((b.links[i].a_B - a.links[i].a_B).norm(), 1e-12);
      EXPECT_LT((b.links[i].b_B - a.links[i].b_B).norm(), 1e-12);
      EXPECT_EQ(b.links[i].radius, a.links[i].radius);
    }
    ASSERT_EQ(b.obstacles.size(), a.obstacles.size());
    for (std::size_t i = 0; i < a.obstacles.size(); ++i) {
      EXPECT_EQ(b.obstacles[i].name, a.obstacles[i].name);
      EXPECT_EQ(b.obstacles[i].shape, a.obstacles[i].shape);
      EXPECT_LT((b.obstacles[i].center.head<2>() - a.obstacles[i].center.head<2>()).norm(), 1e-15);
      EXPECT_EQ(b.obstacles[i].radius, a.obstacles[i].radius);
      EXPECT_LT((b.obstacles[i].size - a.obstacles[i].size).norm(), 1e-15);
      EXPECT_EQ(b.obstacles[i].yaw, a.obstacles[i].yaw);
      EXPECT_NEAR(b.obstacles[i].z_min, a.obstacles[i].z_min, 1e-15);
      EXPECT_NEAR(b.obstacles[i].z_max, a.obstacles[i].z_max, 1e-15);
    }
  }
}

}  // namespace
}  // namespace ccma
