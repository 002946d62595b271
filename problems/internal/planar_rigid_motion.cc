#include "problems/internal/planar_rigid_motion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

namespace ccma {

bool MovesRigidlyWithItsBases(const Model& model) {
  for (const Joint& joint : model.joints) {
    if (joint.body_a == kWorld || joint.body_b == kWorld) return false;
  }
  return model.num_bases() > 0;
}

namespace {

// An angle difference in [-pi, pi]; std::remainder only when needed (it is
// slow, and the differences here are almost always small).
double Wrapped(double d) { return std::abs(d) <= M_PI ? d : std::remainder(d, 2 * M_PI); }

}  // namespace

bool PlanarRigidMotionBetween(const Model& model, const Eigen::VectorXd& u_old, const Eigen::VectorXd& u_new,
                              PlanarRigidMotion* motion) {
  const int num_bases = model.num_bases();
  const int base_controls = model.num_base_controls();
  // (Sizes against the bases only: Model::num_controls() counts the joints,
  // and the caller has checked u against the model.)
  if (num_bases == 0 || u_old.size() < base_controls || u_new.size() != u_old.size()) return false;
  // One pass (this runs before every formation step): the largest change
  // of a control [m or rad], headings the short way round; the largest
  // magnitude; and a probe that is 0 when every control is finite, NaN if not.
  const int n = static_cast<int>(u_old.size());
  const double* a = u_old.data();
  const double* b = u_new.data();
  double change = 0, scale = 0, probe = 0;
  int base = 0, first = 0;  // the base whose heading comes next, and its first control
  for (int i = 0; i < n; ++i) {
    const bool heading = base < num_bases && i == first + kBaseHeading;
    if (heading) first += KindOf(model.mobile_bases[static_cast<size_t>(base++)]).num_controls();
    const double d = b[i] - a[i];
    change = std::max(change, std::abs(heading ? Wrapped(d) : d));
    scale = std::max(scale, std::max(std::abs(a[i]), std::abs(b[i])));
    probe += (a[i] - a[i]) + (b[i] - b[i]);
  }
  if (!(probe == 0) || change == 0) return false;  // not finite, or nothing to predict
  const double tolerance = 1e-10 * change + 8 * std::numeric_limits<double>::epsilon() * (1 + scale);
  // T from the first base: its heading change and where its origin went.
  const double dtheta = Wrapped(u_new[2] - u_old[2]);
  // The rotation as a matrix, once (Rotation2D would take sin and cos at
  // every product); a translation needs neither.
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
  if (dtheta != 0) R = Eigen::Rotation2Dd(dtheta).toRotationMatrix();
  const Eigen::Vector2d t = u_new.head<2>() - R * u_old.head<2>();
  int i = 0;
  for (const MobileBase& b : model.mobile_bases) {
    const Eigen::Vector2d moved = R * u_old.segment<2>(i) + t;
    if (std::abs(moved.x() - u_new[i]) > tolerance || std::abs(moved.y() - u_new[i + 1]) > tolerance ||
        std::abs(Wrapped(u_new[i + 2] - u_old[i + 2] - dtheta)) > tolerance) {
      return false;
    }
    // A legged base's height, roll and pitch turn with the body: they must stay.
    const int next = i + KindOf(b).num_controls();
    for (i += 3; i < next; ++i) {
      if (std::abs(u_new[i] - u_old[i]) > tolerance) return false;
    }
  }
  for (; i < u_old.size(); ++i) {
    if (std::abs(u_new[i] - u_old[i]) > tolerance) return false;  // an actuated joint moved: not rigid
  }
  motion->dtheta = dtheta;
  motion->t = t;
  return true;
}

void ApplyPlanarRigidMotion(const PlanarRigidMotion& motion, State* s) {
  // On the stored poses directly ([qx, qy, qz, qw, px, py, pz], state.h):
  // this runs on every formation step, where it is a third of the solve.
  const double tx = motion.t.x(), ty = motion.t.y();
  if (motion.dtheta == 0) {  // a translation: orientations stay exactly as they are
    for (int body = 0; body < s->num_bodies(); ++body) {
      double* pose = s->pose(body);
      pose[4] += tx;
      pose[5] += ty;
    }
    return;
  }
  const double c = std::cos(motion.dtheta), sn = std::sin(motion.dtheta);
  // q_turn = (w, x, y, z) = (cos(dtheta/2), 0, 0, sin(dtheta/2)); q <- q_turn q.
  const double cw = std::cos(motion.dtheta / 2), sz = std::sin(motion.dtheta / 2);
  for (int body = 0; body < s->num_bodies(); ++body) {
    double* pose = s->pose(body);
    const double x = pose[0], y = pose[1], z = pose[2], w = pose[3];
    pose[0] = cw * x - sz * y;
    pose[1] = cw * y + sz * x;
    pose[2] = cw * z + sz * w;
    pose[3] = cw * w - sz * z;
    const double px = pose[4], py = pose[5];
    pose[4] = c * px - sn * py + tx;
    pose[5] = sn * px + c * py + ty;
  }
}

}  // namespace ccma
