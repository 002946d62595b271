// `type: legged`: a quadruped that carries the chain on its body, which it
// raises, lowers and tilts while it stands (docs/model_format.md, "Legged
// agents"). Six controls: x, y, heading, height, roll, pitch; the body's
// rotation is Rz(heading) Ry(pitch) Rx(roll) about its own origin, which
// stays at (x, y, height).
#include <cmath>

#include <ceres/cost_function.h>

#include "ccma/bases/base_kinds.h"
#include "ccma/model.h"
#include "ccma/rotation.h"
#include "cost_functions/legged_base_motor_cost.h"

namespace ccma {
namespace {

class LeggedBaseKind final : public BaseKind {
 public:
  const char* name() const override { return "legged"; }
  const std::vector<BaseControl>& controls() const override {
    static const std::vector<BaseControl> controls = {{"x", "m"},      {"y", "m"},    {"theta", "rad"},
                                                      {"height", "m"}, {"roll", "rad"}, {"pitch", "rad"}};
    return controls;
  }
  Eigen::VectorXd HomeControls(const MobileBase& base) const override {
    Eigen::VectorXd u(kLeggedControlSize);
    u << base.home_pose.x(), base.home_pose.y(), base.home_pose.z(), base.legged.height, 0.0, 0.0;
    return u;
  }
  void HomeFrame(const MobileBase& base, Eigen::Matrix3d* R_WB, Eigen::Vector3d* p_WB) const override {
    *R_WB = RotationZ(base.home_pose.z());
    *p_WB = Eigen::Vector3d(base.home_pose.x(), base.home_pose.y(), base.legged.height);
  }
  std::vector<ControlRange> Limits(const MobileBase& base) const override {
    std::vector<ControlRange> limits(kLeggedControlSize);
    limits[3] = base.legged.height_limits;
    limits[4] = base.legged.roll_limits;
    limits[5] = base.legged.pitch_limits;
    return limits;
  }
  // With a footprint, a box along its heading from the floor to its body.
  BaseCollisionShape CollisionShape(const MobileBase& base) const override {
    BaseCollisionShape shape;
    shape.rectangle = base.legged.footprint.x() > 0;
    shape.half_size = 0.5 * base.legged.footprint;
    return shape;
  }
  std::vector<BaseConstraint> Constraints(const MobileBase& /*base*/, bool autodiff) const override {
    std::vector<BaseConstraint> out(1);
    out[0].cost.reset(autodiff ? MakeLeggedBaseMotorAutoDiff() : new LeggedBaseMotorCost());
    out[0].reads_controls = true;
    out[0].part = "motor";
    return out;
  }
  int num_residuals() const override { return LeggedBaseMotorCost::kNumResiduals; }
  // The wrench the body exerts on the chain: force, then moment about the
  // body frame's origin, world axes.
  std::vector<BaseEffort> Efforts(const double* u, const double* effort) const override {
    const Eigen::Matrix<double, 6, 1> w = LeggedBodyWrench(u, effort);
    return {{"base_force_x", w[3]},  {"base_force_y", w[4]},  {"base_force_z", w[5]},
            {"base_moment_x", w[0]}, {"base_moment_y", w[1]}, {"base_moment_z", w[2]}};
  }
};

}  // namespace

Eigen::Matrix<double, 6, 1> LeggedBodyWrench(const double* u, const double* effort) {
  // Twist per control: x, y, height translate along e_x, e_y, e_z; heading,
  // roll and pitch turn about a = e_z, b = Rz Ry e_x, c = Rz e_y. With
  // M = [a b c], the moment m solves M^T m = (e_heading, e_roll, e_pitch):
  // m = ((b x c) e_heading + (c x a) e_roll + (a x b) e_pitch) / det M.
  const double ch = std::cos(u[2]), sh = std::sin(u[2]), cp = std::cos(u[5]), sp = std::sin(u[5]);
  const Eigen::Vector3d a = Eigen::Vector3d::UnitZ(), b(ch * cp, sh * cp, -sp), c(-sh, ch, 0.0);
  const double det = a.dot(b.cross(c));
  Eigen::Matrix<double, 6, 1> wrench = Eigen::Matrix<double, 6, 1>::Zero();
  if (std::abs(det) > 1e-12) {
    wrench.head<3>() = (b.cross(c) * effort[2] + c.cross(a) * effort[4] + a.cross(b) * effort[5]) / det;
  }
  wrench.tail<3>() << effort[0], effort[1], effort[3];
  return wrench;
}

const BaseKind& LeggedBase() {
  static const LeggedBaseKind kind;
  return kind;
}

}  // namespace ccma
