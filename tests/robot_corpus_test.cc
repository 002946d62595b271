// Public closed-loop robot files, imported unedited (tests/data/corpus/: each
// folder's SOURCE says where a file comes from, its LICENSE the terms), each
// checked against a closed form written here from the file's own numbers:
// the end-effector at several crank angles (1e-9 m) and a statics effort by
// virtual work with the file's masses and gravity (1e-9 relative).
//
// Every file of the corpus is a four-bar: two pivots on the ground (A, the
// crank's; D, the rocker's), the crank's far pivot B and the coupler's far
// pivot C, all four axes parallel (unit n). Its closed form, in the plane
// normal to n: B turns about A by the crank angle q; C is where the circles
// of radius |C0 B0| about B and |C0 D| about D meet, on the branch of C0;
// the coupler turns by phi = angle(C - B) - angle(C0 - B0), the rocker by
// psi = angle(C - D) - angle(C0 - D). Derivatives by differentiating those
// relations (a 2 x 2 solve for dC/dq), so the statics check is exact too.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "analyses/robot_import.h"
#include "analyses/statics.h"
#include "formats/model_loader.h"
#include "formats/sdformat_reader.h"
#include "problems/forward_problem.h"

namespace ccma {
namespace robot_corpus_test {

const std::string kCorpus = std::string(CCMA_TEST_DATA_DIR) + "/corpus/";

Eigen::Matrix3d Rx(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix(); }
Eigen::Matrix3d Ry(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
Eigen::Matrix3d Rz(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }
// SDFormat's pose x y z roll pitch yaw: R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Isometry3d Pose(double x, double y, double z, double roll, double pitch, double yaw) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Rz(yaw) * Ry(pitch) * Rx(roll);
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}
constexpr double kDegree = M_PI / 180;

// A rigid point of a link of the four-bar at crank angle q and its rate.
struct Moving {
  Eigen::Vector3d p, dp_dq;
};

class FourBar {
 public:
  // The four pivots at q = 0 (world, m) and the common axis n (the crank's,
  // the sense in which q turns it).
  FourBar(const Eigen::Vector3d& A, const Eigen::Vector3d& B0, const Eigen::Vector3d& C0, const Eigen::Vector3d& D,
          const Eigen::Vector3d& n)
      : A_(A), B0_(B0), C0_(C0), D_(D), n_(n.normalized()) {
    e1_ = (B0 - A - n_.dot(B0 - A) * n_).normalized();
    e2_ = n_.cross(e1_);
    branch_ = Cross(In(D_) - In(B0_), In(C0_) - In(B0_)) > 0;
  }

  // Sets the crank angle [rad]; false when the loop cannot close there.
  bool Set(double q) {
    q_ = q;
    b_ = In(A_) + Turn(q, In(B0_) - In(A_));
    const Eigen::Vector2d d = In(D_);
    const double r2 = (In(C0_) - In(B0_)).norm(), r3 = (In(C0_) - d).norm(), l = (d - b_).norm();
    const double a = (r2 * r2 - r3 * r3 + l * l) / (2 * l), h2 = r2 * r2 - a * a;
    if (h2 < 0) return false;
    const Eigen::Vector2d u = (d - b_) / l, normal(-u.y(), u.x());
    // The two meeting points lie either side of the line b-d: C0's side.
    c_ = b_ + a * u + std::sqrt(h2) * normal;
    if ((Cross(d - b_, c_ - b_) > 0) != branch_) c_ = b_ + a * u - std::sqrt(h2) * normal;
    // Rates: db = J (b - a); (c - b).(dc - db) = 0 and (c - d).dc = 0.
    db_ = Perp(b_ - In(A_));
    Eigen::Matrix2d M;
    M.row(0) = (c_ - b_).transpose();
    M.row(1) = (c_ - d).transpose();
    dc_ = M.inverse() * Eigen::Vector2d((c_ - b_).dot(db_), 0.0);
    phi_ = Angle(c_ - b_) - Angle(In(C0_) - In(B0_));
    dphi_ = Cross(c_ - b_, dc_ - db_) / (c_ - b_).squaredNorm();
    psi_ = Angle(c_ - d) - Angle(In(C0_) - d);
    dpsi_ = Cross(c_ - d, dc_) / (c_ - d).squaredNorm();
    return true;
  }

  // A point fixed in the crank, the coupler or the rocker (its place at q = 0).
  Moving Crank(const Eigen::Vector3d& p0) const { return About(A_, q_, 1.0, p0); }
  Moving Rocker(const Eigen::Vector3d& p0) const { return About(D_, psi_, dpsi_, p0); }
  Moving Coupler(const Eigen::Vector3d& p0) const {
    const Moving B = Crank(B0_);
    const Eigen::Vector3d p = B.p + Rotation(phi_) * (p0 - B0_);
    return {p, B.dp_dq + dphi_ * n_.cross(p - B.p)};
  }

 private:
  Eigen::Vector2d In(const Eigen::Vector3d& p) const { return {e1_.dot(p), e2_.dot(p)}; }
  static Eigen::Vector2d Turn(double a, const Eigen::Vector2d& v) { return Eigen::Rotation2Dd(a) * v; }
  static Eigen::Vector2d Perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }
  static double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
  static double Angle(const Eigen::Vector2d& v) { return std::atan2(v.y(), v.x()); }
  Eigen::Matrix3d Rotation(double a) const { return Eigen::AngleAxisd(a, n_).toRotationMatrix(); }
  Moving About(const Eigen::Vector3d& pivot, double angle, double rate, const Eigen::Vector3d& p0) const {
    const Eigen::Vector3d p = pivot + Rotation(angle) * (p0 - pivot);
    return {p, rate * n_.cross(p - pivot)};
  }

  Eigen::Vector3d A_, B0_, C0_, D_, n_, e1_, e2_;
  bool branch_ = true;
  double q_ = 0, phi_ = 0, dphi_ = 0, psi_ = 0, dpsi_ = 0;
  Eigen::Vector2d b_, c_, db_, dc_;
};

// One file of the corpus: how it is imported, its closed form, its masses.
struct CorpusRobot {
  std::string file, crank_joint, ee_link;
  Eigen::Vector3d ee_point_L = Eigen::Vector3d::Zero();
  FourBar four_bar;
  Eigen::Vector3d P0;  // the end-effector point at q = 0, on the coupler (world)
  // The link origins (= their centres of mass, as the file gives them or
  // SDFormat's default puts them) of crank, coupler and rocker at q = 0, and
  // the mass of each [kg].
  Eigen::Vector3d crank_com, coupler_com, rocker_com;
  double crank_mass, coupler_mass, rocker_mass;
  Eigen::Vector3d gravity;
  std::vector<double> angles;  // crank angles to check [rad]
};

// gz-physics anchored_loop.sdf (SDFormat 1.6 world, gravity 0 -9.8 0, no
// <inertial>: 1 kg at each link's origin), and gazebo-classic's copy of it
// as a world with its ground plane and sun included (gravity: SDFormat's
// default for a world). The loop lies in the y-z plane, axes along +x.
CorpusRobot AnchoredLoop(const std::string& file, const Eigen::Vector3d& gravity) {
  const Eigen::Vector3d A(0, 0, 0.2), B0(0.1, -0.3, 0.6), C0(0, -0.8, 0.6);
  const Eigen::Vector3d D = C0 + Rx(2.4981) * Eigen::Vector3d(0, 0, 0.5);  // joint4: (0 0 0.5) in link3
  const Eigen::Vector3d P0 = B0 + Rx(1.5708) * Eigen::Vector3d(0, 0, 0.25);
  return {file, "joint1", "link2", {0, 0, 0.25}, FourBar(A, B0, C0, D, Eigen::Vector3d::UnitX()), P0,
          A, B0, C0, 1, 1, 1, gravity, {0, 0.3, -0.2}};
}

// gazebosim/sdformat four_bar.sdf (1.6 model, no joint to world: its first
// link, link1, is welded where it is): a 0.4 m square in a horizontal
// plane, 0.1 kg per link at its origin, axes along z; joint poses are in
// the child link's frame.
CorpusRobot SdformatFourBar() {
  const double z = 0.05;
  const Eigen::Vector3d A(0.2, 0.2, z), B0(0.2, -0.2, z), C0(-0.2, -0.2, z), D(-0.2, 0.2, z);
  const Eigen::Vector3d link2(0.2, 0, z), link3(0, -0.2, z), link4(-0.2, 0, z);
  return {"sdformat/four_bar.sdf", "joint1", "link3", {0, 0, 0}, FourBar(A, B0, C0, D, Eigen::Vector3d::UnitZ()),
          link3, link2, link3, link4, 0.1, 0.1, 0.1, Eigen::Vector3d(0, 0, -9.81), {0, 0.3, -0.5, 1.0}};
}

// gz-physics free_loop.sdf (1.6 world, a static ground plane beside the
// model, gravity 0 0 -9.8, no <inertial>): a square loop posed by the
// model's pose, floating free: link_0 welded. Every joint is (0 -0.4 0) in
// its child's frame.
CorpusRobot FreeLoop() {
  const Eigen::Isometry3d X_WM = Pose(0, 0, 0.8, 1.5708, 0.7854, 0);
  const Eigen::Isometry3d link1 = X_WM * Pose(0, 0.4, 0.1, 0, 0, -1.5708);
  const Eigen::Isometry3d link2 = X_WM * Pose(0.4, 0, 0, 0, 0, -3.14159);
  const Eigen::Isometry3d link3 = X_WM * Pose(0, -0.4, 0.1, 0, 0, 1.5708);
  const Eigen::Isometry3d link0 = X_WM * Pose(-0.4, 0, 0, 0, 0, 0);
  const Eigen::Vector3d joint(0, -0.4, 0);
  const Eigen::Vector3d A = link1 * joint, B0 = link2 * joint, C0 = link3 * joint, D = link0 * joint;
  const Eigen::Vector3d n = link1.linear() * Eigen::Vector3d::UnitZ();
  return {"gz_physics/free_loop.sdf", "joint_0_1", "link_2", {0, 0, 0}, FourBar(A, B0, C0, D, n),
          link2.translation(), link1.translation(), link2.translation(), link3.translation(), 1, 1, 1,
          Eigen::Vector3d(0, 0, -9.8), {0, 0.3, -0.3}};
}

// gz-physics closed_loop_four_bar_linkage.sdf (SDFormat 1.11 world, poses in
// degrees and relative to <frame>s, a static ground plane, the model's base
// of 2500 kg welded, <inertial auto="true"> read as SDFormat's default 1 kg
// at the link origin, gravity SDFormat's default for a world): two upper
// links of 0.5 m hang from a pole, 0.6 m apart, joined by a lower link.
CorpusRobot PoleFourBar() {
  const Eigen::Isometry3d X_WM = Pose(-4.7, 1, 0, 0, 0, 180 * kDegree);
  const Eigen::Isometry3d pole_top = X_WM * Pose(0, 0, 0.01, 0, 0, 0) * Pose(-0.275, 0, 1.95, 0, 0, 0) *
                                     Pose(0.1, 0, 1.95, 0, 0, 0);
  const Eigen::Isometry3d left = pole_top * Pose(0, -0.3, -0.05, 0, 0, 0) * Pose(0.15, 0, 0, -155 * kDegree, 0, 0);
  const Eigen::Isometry3d right = pole_top * Pose(0, 0.3, -0.05, 0, 0, 0) * Pose(0.15, 0, 0, -155 * kDegree, 0, 0);
  const Eigen::Isometry3d left_mount = left * Pose(0, 0, 0.5, 0, 0, 0);
  const Eigen::Isometry3d right_mount = right * Pose(0, 0, 0.5, 0, 0, 0);
  const Eigen::Isometry3d lower_left_joint = left_mount * Pose(0, 0, 0, -25 * kDegree, 0, 0);
  const Eigen::Vector3d lower = lower_left_joint * Eigen::Vector3d(0, -0.3, 0.2);
  const Eigen::Vector3d n = left.linear() * Eigen::Vector3d::UnitX();  // the axis, in the joint (= link) frame
  return {"gz_physics/closed_loop_four_bar_linkage.sdf", "upper_left_joint", "lower_link", {0, 0, 0},
          FourBar(left.translation(), left_mount.translation(), right_mount.translation(), right.translation(), n),
          lower, left.translation(), lower, right.translation(), 1, 1, 1, Eigen::Vector3d(0, 0, -9.8),
          {0, 0.4, -0.4}};
}

ImportedRobot Import(const CorpusRobot& r) {
  ImportOptions options;
  options.actuated = {r.crank_joint};
  options.end_effector_link = r.ee_link;
  options.end_effector_point_L = r.ee_point_L;
  return ImportRobot(ReadSdformat(kCorpus + r.file, {}), options);
}

// The crank's effort holding the file's masses under its gravity and a
// force F at the end-effector point, by virtual work: -sum F_i . dp_i/dq.
double HandEffort(const CorpusRobot& r, FourBar& bar, const Eigen::Vector3d& F) {
  return -(r.crank_mass * r.gravity.dot(bar.Crank(r.crank_com).dp_dq) +
           r.coupler_mass * r.gravity.dot(bar.Coupler(r.coupler_com).dp_dq) +
           r.rocker_mass * r.gravity.dot(bar.Rocker(r.rocker_com).dp_dq) + F.dot(bar.Coupler(r.P0).dp_dq));
}

void ExpectTheRobotItDescribes(CorpusRobot r) {
  SCOPED_TRACE(r.file);
  const ImportedRobot imported = Import(r);
  const Model& model = imported.model;
  ASSERT_EQ(model.num_controls(), 1);
  EXPECT_EQ(imported.closures, 1);
  ASSERT_EQ(imported.closure_gaps.size(), 1u);  // the source's own loop joint, gap 0
  EXPECT_LT((model.gravity - r.gravity).norm(), 1e-15);
  const Eigen::Vector3d F(1.5, -2, 3);  // N, at the end-effector point
  for (const double q : r.angles) {
    ASSERT_TRUE(r.four_bar.Set(q)) << q;
    ForwardProblem forward(model);
    const ForwardResult result = forward.Assemble(Eigen::VectorXd::Constant(1, q));
    ASSERT_TRUE(result.assembled) << q << ": E = " << result.residual_energy;
    const Moving P = r.four_bar.Coupler(r.P0);
    EXPECT_LT((forward.end_effector().position - P.p).norm(), 1e-9) << "q = " << q << "\n"
                                                                    << forward.end_effector().position.transpose()
                                                                    << "\n" << P.p.transpose();
    ExternalWrench wrench;
    wrench.force = F;
    const StaticsReport statics = ComputeStatics(model, forward.state(), forward.controls(), wrench);
    ASSERT_EQ(statics.actuators.size(), 1u);
    const double hand = HandEffort(r, r.four_bar, F);
    EXPECT_NEAR(statics.actuators[0].effort, hand, 1e-9 * std::max(1.0, std::abs(hand))) << "q = " << q;
  }
}

TEST(RobotCorpus, GzPhysicsAnchoredLoopIsTheFourBarItDescribesWithItsWorldsGravity) {
  ExpectTheRobotItDescribes(AnchoredLoop("gz_physics/anchored_loop.sdf", Eigen::Vector3d(0, -9.8, 0)));
}

TEST(RobotCorpus, GazeboClassicWorldWithIncludesIsTheSameFourBar) {
  ExpectTheRobotItDescribes(AnchoredLoop("gazebo_classic/anchored_loop.world", Eigen::Vector3d(0, 0, -9.8)));
  // Its ground plane and sun are included from Gazebo's model path: skipped,
  // each said.
  const RobotDescription robot = ReadSdformat(kCorpus + "gazebo_classic/anchored_loop.world", {"joint1"});
  int skipped = 0;
  for (const std::string& w : robot.warnings) skipped += w.find("<include> of 'model://") != std::string::npos;
  EXPECT_EQ(skipped, 2);
}

TEST(RobotCorpus, SdformatFourBarFloatingFreeIsWeldedAtItsFirstLink) {
  ExpectTheRobotItDescribes(SdformatFourBar());
  // The weld carries the whole weight (0.4 kg: the file's four masses).
  const ImportedRobot imported = Import(SdformatFourBar());
  ForwardProblem forward(imported.model);
  ASSERT_TRUE(forward.Assemble(Eigen::VectorXd::Constant(1, 0.3)).assembled);
  const StaticsReport statics = ComputeStatics(imported.model, forward.state(), forward.controls());
  bool found = false;
  for (const JointReaction& j : statics.joints) {
    if (j.name != "world__link1") continue;
    found = true;
    EXPECT_NEAR(j.force.z(), 0.4 * 9.81, 1e-12);
  }
  EXPECT_TRUE(found);
}

TEST(RobotCorpus, GzPhysicsFreeLoopInAWorldWithAGroundPlane) { ExpectTheRobotItDescribes(FreeLoop()); }

TEST(RobotCorpus, GzPhysicsSdformat1_11FourBarWithFramesAndDegrees) { ExpectTheRobotItDescribes(PoleFourBar()); }

// ArchiRob/delta_2's delta robot (SDFormat 1.4 model: every <axis><xyz> in
// the model frame, 1.4's meaning; no joint to world). Three motorised arms,
// each carrying a parallelogram of two ball-ball rods to the platform, which
// therefore only translates: its position t is where three spheres meet, of
// radius the rod length about each arm's ball-pair midpoint less the
// platform's ball-pair midpoint (the ideal delta's closed form). Numbers as
// the file writes them (its rounded yaws put the rods about 1e-7 m off an
// exact parallelogram, which moves the platform by less than 1e-12 m).
class Delta {
 public:
  Delta() {
    const double yaw[3] = {0.523599, 2.61799, 4.71239};
    const Eigen::Vector3d proximal[3] = {{0.1299037937375349, 0.07500002915063418, 0.02},
                                         {-0.1299037937375349, 0.07500002915063418, 0.02},
                                         {0.0, -0.15, 0.02}};
    axis_[0] = Eigen::Vector3d(0.5000001943375613, -0.8660252915835662, 0).normalized();
    axis_[1] = Eigen::Vector3d(0.5000001943375613, 0.8660252915835662, 0).normalized();
    axis_[2] = Eigen::Vector3d(-1, 0, 0);
    // The distal links' poses (two per arm) and the platform's balls, in the file's order.
    const Eigen::Vector3d distal[6] = {{0.13133329519352216, 0.032524076829499225, 0.12917082497169285},
                                       {0.09383328061820506, 0.0974759736982667, 0.12917082497169285},
                                       {-0.09383328061820506, 0.0974759736982667, 0.12917082497169285},
                                       {-0.13133329519352216, 0.032524076829499225, 0.12917082497169285},
                                       {-0.0375, -0.13, 0.12917082497169285},
                                       {0.0375, -0.13, 0.12917082497169285}};
    const Eigen::Vector3d platform_ball[6] = {{0.06205127186683686, -0.007475938717505671, 0},
                                              {0.02455125729151977, 0.0574759581512618, 0},
                                              {-0.02455125729151977, 0.0574759581512618, 0},
                                              {-0.06205127186683686, -0.007475938717505671, 0},
                                              {-0.0375, -0.05, 0},
                                              {0.0375, -0.05, 0}};
    t0_ = Eigen::Vector3d(0, 0, 0.23834164994338572);
    for (int i = 0; i < 3; ++i) {
      // The arm's pivot: joint pose (-0.06 0 0) in the proximal link's frame.
      pivot_[i] = proximal[i] + Rz(yaw[i]) * Eigen::Vector3d(-0.06, 0, 0);
      Eigen::Vector3d arm_balls = Eigen::Vector3d::Zero(), platform_balls = Eigen::Vector3d::Zero();
      double length = 0;
      for (int k = 2 * i; k < 2 * i + 2; ++k) {
        // The arm's ball: joint pose (0.135345 0 0) in the distal link's frame.
        const Eigen::Vector3d ball = distal[k] + (Rz(yaw[i]) * Ry(0.9383966687035906) * Rx(1.57075)) *
                                                     Eigen::Vector3d(0.135345, 0, 0);
        arm_balls += 0.5 * ball;
        platform_balls += 0.5 * platform_ball[k];
        length += 0.5 * (t0_ + platform_ball[k] - ball).norm();
      }
      arm_ball0_[i] = arm_balls;
      platform_offset_[i] = platform_balls;
      length_[i] = length;
    }
  }

  // The platform's position at the arms' angles u [rad], and dt/du (3 x 3).
  Eigen::Vector3d At(const Eigen::Vector3d& u, Eigen::Matrix3d* dt_du) const {
    Eigen::Vector3d c[3], dc[3];
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d ball = pivot_[i] + Eigen::AngleAxisd(u[i], axis_[i]) * (arm_ball0_[i] - pivot_[i]);
      c[i] = ball - platform_offset_[i];
      dc[i] = axis_[i].cross(ball - pivot_[i]);
    }
    // Three spheres: two solutions mirrored about the centres' plane; the
    // one on the home side.
    const Eigen::Vector3d ex = (c[1] - c[0]).normalized();
    const double d = (c[1] - c[0]).norm(), i = ex.dot(c[2] - c[0]);
    const Eigen::Vector3d ey = (c[2] - c[0] - i * ex).normalized(), ez = ex.cross(ey);
    const double j = ey.dot(c[2] - c[0]);
    const double x = (length_[0] * length_[0] - length_[1] * length_[1] + d * d) / (2 * d);
    const double y = (length_[0] * length_[0] - length_[2] * length_[2] + i * i + j * j) / (2 * j) - i / j * x;
    const double z = std::sqrt(length_[0] * length_[0] - x * x - y * y);
    const Eigen::Vector3d a = c[0] + x * ex + y * ey + z * ez, b = c[0] + x * ex + y * ey - z * ez;
    const Eigen::Vector3d t = (a - t0_).norm() < (b - t0_).norm() ? a : b;
    // (t - c_i) . (dt - dc_i du_i) = 0 for each arm.
    Eigen::Matrix3d M;
    for (int k = 0; k < 3; ++k) M.row(k) = (t - c[k]).transpose();
    Eigen::Matrix3d rhs = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 3; ++k) rhs(k, k) = (t - c[k]).dot(dc[k]);
    *dt_du = M.inverse() * rhs;
    return t;
  }

 private:
  Eigen::Vector3d axis_[3], pivot_[3], arm_ball0_[3], platform_offset_[3], t0_;
  double length_[3];
};

TEST(RobotCorpus, DeltaInSdformat1_4IsTheDeltaItDescribes) {
  const std::string file = kCorpus + "delta_2/delta_robot.model.sdf";
  const RobotDescription robot =
      ReadSdformat(file, {"proximal_link_1_joint", "proximal_link_3_joint", "proximal_link_5_joint"});
  // Its rods and platform are weightless in Gazebo; ccma weighs them, and says so.
  int said = 0;
  for (const std::string& w : robot.warnings) said += w.find("<gravity>false</gravity>") != std::string::npos;
  EXPECT_EQ(said, 1);
  ImportOptions options;
  options.end_effector_link = "platform_link";
  const ImportedRobot imported = ImportRobot(robot, options);
  const Model& model = imported.model;
  ASSERT_EQ(model.num_controls(), 3);
  EXPECT_EQ(imported.closures, 5);  // six rods to one platform
  EXPECT_EQ(imported.closure_gaps.size(), 5u);
  const Delta delta;
  const Eigen::Vector3d F(2, -1, -5);  // N, at the platform's origin
  for (const Eigen::Vector3d u : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.3, 0.3, 0.3),
                                  Eigen::Vector3d(0.2, -0.1, 0.4), Eigen::Vector3d(-0.5, 0.6, 0.1)}) {
    Eigen::Matrix3d dt_du;
    const Eigen::Vector3d t = delta.At(u, &dt_du);
    ForwardProblem forward(model);
    ASSERT_TRUE(forward.Assemble(u).assembled) << u.transpose();
    EXPECT_LT((forward.end_effector().position - t).norm(), 1e-9) << u.transpose();
    EXPECT_LT(forward.end_effector().rpy.norm(), 1e-9) << u.transpose();  // it translates
    // The motors' efforts against F by virtual work, -F . dt/du: the
    // difference of statics with and without F (the weights cancel).
    ExternalWrench wrench;
    wrench.force = F;
    const StaticsReport loaded = ComputeStatics(model, forward.state(), forward.controls(), wrench);
    const StaticsReport unloaded = ComputeStatics(model, forward.state(), forward.controls());
    for (int k = 0; k < 3; ++k) {
      const double hand = -F.dot(dt_du.col(k));
      EXPECT_NEAR(loaded.actuators[k].effort - unloaded.actuators[k].effort, hand, 1e-9 * std::abs(hand) + 1e-12)
          << "motor " << k << " at " << u.transpose();
    }
  }
}

// The delta's 1.4 file and its hand conversion to 1.7 (each axis
// expressed_in the model frame, 1.4's meaning) import body by body as the
// same robot; the 1.4 file with only its version changed is another robot
// (its axes then in the joint frames: the motors move x, y, roll, not z).
TEST(RobotCorpus, TheDeltaIn1_4EqualsItsHandConversionTo1_7BodyByBody) {
  const std::vector<std::string> motors = {"proximal_link_1_joint", "proximal_link_3_joint", "proximal_link_5_joint"};
  ImportOptions options;
  options.end_effector_link = "platform_link";
  const std::string folder = kCorpus + "delta_2/";
  const ImportedRobot v14 = ImportRobot(ReadSdformat(folder + "delta_robot.model.sdf", motors), options);
  const ImportedRobot v17 = ImportRobot(ReadSdformat(folder + "delta_robot_1_7_hand_converted.sdf", motors), options);
  ASSERT_EQ(v14.model.num_bodies(), v17.model.num_bodies());
  ASSERT_EQ(v14.model.joints.size(), v17.model.joints.size());
  for (int b = 0; b < v14.model.num_bodies(); ++b) {
    const Body& a = v14.model.bodies[b];
    const Body& c = v17.model.bodies[v17.model.FindBody(a.name)];
    EXPECT_LT((a.p_WB_home - c.p_WB_home).norm(), 1e-12) << a.name;
    EXPECT_LT((a.R_WB_home - c.R_WB_home).norm(), 1e-12) << a.name;
    EXPECT_NEAR(a.inertia.mass, c.inertia.mass, 1e-15) << a.name;
  }
  EXPECT_EQ(v14.controlled, v17.controlled);
  for (const Eigen::Vector3d u : {Eigen::Vector3d(0.3, -0.2, 0.1), Eigen::Vector3d(-0.4, 0.2, 0.5)}) {
    ForwardProblem a(v14.model), c(v17.model);
    ASSERT_TRUE(a.Assemble(u).assembled && c.Assemble(u).assembled);
    EXPECT_LT((a.end_effector().position - c.end_effector().position).norm(), 1e-12);
  }
  std::string text, error;
  ASSERT_TRUE(internal::ReadRegularFile(folder + "delta_robot.model.sdf", 1 << 20, "file", &text, &error)) << error;
  text.replace(text.find("version=\"1.4\""), 13, "version=\"1.7\"");
  const ImportedRobot bumped = ImportRobot(ReadSdformatFromString(text, "bumped.sdf", motors), options);
  EXPECT_NE(bumped.controlled, v14.controlled);  // x, y, roll instead of x, y, z
}

// The closed form can fail: the anchored loop's crank cannot turn to -0.4
// (the bars would need 1.093 m; they reach 1.0), and ccma says so too.
TEST(RobotCorpus, TheClosedFormAndTheImportAgreeWhereTheLoopCannotClose) {
  CorpusRobot r = AnchoredLoop("gz_physics/anchored_loop.sdf", Eigen::Vector3d(0, -9.8, 0));
  EXPECT_FALSE(r.four_bar.Set(-0.4));
  const ImportedRobot imported = Import(r);
  ForwardProblem forward(imported.model);
  EXPECT_FALSE(forward.Assemble(Eigen::VectorXd::Constant(1, -0.4)).assembled);
  // And a wrong closed form is caught: the coupler point off by 1 mm fails the 1e-9 check.
  ASSERT_TRUE(r.four_bar.Set(0.3));
  ForwardProblem at(imported.model);
  ASSERT_TRUE(at.Assemble(Eigen::VectorXd::Constant(1, 0.3)).assembled);
  const Eigen::Vector3d off = r.four_bar.Coupler(r.P0 + Eigen::Vector3d(0, 1e-3, 0)).p;
  EXPECT_GT((at.end_effector().position - off).norm(), 1e-4);
}

}  // namespace robot_corpus_test
}  // namespace ccma
