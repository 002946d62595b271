#include "problems/internal/control_motion.h"

#include <stdexcept>
#include <string>

#include "ccma/limits.h"

namespace ccma {

ControlMotion::ControlMotion(const ConstraintSet& set, const State& s, const Eigen::VectorXd& u)
    : set_(set), s_(s), u_(u) {
  if (static_cast<long>(set.num_rows()) * set.state_size() > kMaxStaticsEntries) {
    throw std::invalid_argument("dynamics: " + std::to_string(set.num_rows()) + " constraint rows x " +
                                std::to_string(set.state_size()) + " state coordinates exceed " +
                                std::to_string(kMaxStaticsEntries) + " entries");
  }
  Eigen::VectorXd C;
  set.Evaluate(s, u, &C, &J_s_, &J_u_);
  cod_.setThreshold(1e-10);
  cod_.compute(J_s_);
}

Eigen::VectorXd ControlMotion::Velocity(const Eigen::VectorXd& du) const {
  return cod_.solve(-(J_u_ * du));
}

Eigen::VectorXd ControlMotion::Acceleration(const Eigen::VectorXd& du, const Eigen::VectorXd& ddu,
                                            const Eigen::VectorXd& ds) const {
  Eigen::VectorXd h;
  set_.CurvatureAlong(s_, u_, ds, du, &h, &frames_);
  return cod_.solve(-(J_u_ * ddu) - h);
}

double ControlMotion::Inconsistency(const Eigen::VectorXd& ds, const Eigen::VectorXd& du) const {
  if (J_s_.rows() == 0) return 0.0;
  return (J_s_ * ds + J_u_ * du).lpNorm<Eigen::Infinity>();
}

}  // namespace ccma
