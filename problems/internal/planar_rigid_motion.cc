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

bool PlanarRigidMotionBetween(const Model& model, const Eigen::VectorXd& u_old, const Eigen::VectorXd& u_new,
                              PlanarRigidMotion* motion) {
  const int num_bases = model.num_bases();
  if (num_bases == 0 || u_old.size() != model.num_controls() || u_new.size() != u_old.size()) return false;
  if (!u_old.allFinite() || !u_new.allFinite() || u_old == u_new) return false;
  double change = 0;  // largest change of a control [m or rad], headings the short way round
  for (int i = 0; i < u_old.size(); ++i) {
    const bool heading = i < kBaseControlSize * num_bases && i % kBaseControlSize == 2;
    const double d = heading ? std::remainder(u_new[i] - u_old[i], 2 * M_PI) : u_new[i] - u_old[i];
    change = std::max(change, std::abs(d));
  }
  const double scale = std::max(u_old.lpNorm<Eigen::Infinity>(), u_new.lpNorm<Eigen::Infinity>());
  const double tolerance = 1e-10 * change + 8 * std::numeric_limits<double>::epsilon() * (1 + scale);
  // T from the first base: its heading change and where its origin went.
  const double dtheta = std::remainder(u_new[2] - u_old[2], 2 * M_PI);
  const Eigen::Rotation2Dd R(dtheta);
  const Eigen::Vector2d t = u_new.head<2>() - R * u_old.head<2>();
  for (int k = 0; k < num_bases; ++k) {
    const int i = kBaseControlSize * k;
    const Eigen::Vector2d moved = R * u_old.segment<2>(i) + t;
    if (std::abs(moved.x() - u_new[i]) > tolerance || std::abs(moved.y() - u_new[i + 1]) > tolerance ||
        std::abs(std::remainder(u_new[i + 2] - u_old[i + 2] - dtheta, 2 * M_PI)) > tolerance) {
      return false;
    }
  }
  for (int i = kBaseControlSize * num_bases; i < u_old.size(); ++i) {
    if (std::abs(u_new[i] - u_old[i]) > tolerance) return false;  // an actuated joint moved: not rigid
  }
  motion->dtheta = dtheta;
  motion->t = t;
  return true;
}

void ApplyPlanarRigidMotion(const PlanarRigidMotion& motion, State* s) {
  const Eigen::Quaterniond q_turn(Eigen::AngleAxisd(motion.dtheta, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d t(motion.t.x(), motion.t.y(), 0.0);
  for (int body = 0; body < s->num_bodies(); ++body) {
    s->SetPose(body, (q_turn * s->q_WB(body)).normalized(), q_turn * s->p_WB(body) + t);
  }
}

}  // namespace ccma
