#include "problems/internal/control_motion.h"

namespace ccma {

ControlMotion::ControlMotion(const ConstraintSet& set, const HessianSolver& symbolic, const State& s,
                             const Eigen::VectorXd& u)
    : set_(set), s_(s), u_(u), factorization_(set, symbolic, s, u) {}

Eigen::VectorXd ControlMotion::Velocity(const Eigen::VectorXd& du) const { return factorization_.StateMotion(du); }

Eigen::VectorXd ControlMotion::Acceleration(const Eigen::VectorXd& du, const Eigen::VectorXd& ddu,
                                            const Eigen::VectorXd& ds) const {
  Eigen::VectorXd h;
  set_.CurvatureAlong(s_, u_, ds, du, &h, &frames_);
  return factorization_.StateSolution(-(J_u() * ddu) - h);
}

double ControlMotion::Inconsistency(const Eigen::VectorXd& ds, const Eigen::VectorXd& du) const {
  if (J_s().rows() == 0) return 0.0;
  return (J_s() * ds + J_u() * du).lpNorm<Eigen::Infinity>();
}

}  // namespace ccma
