#include "ccma/omni_wheels.h"

#include <cmath>
#include <stdexcept>

#include "ccma/internal/dense_factorizations.h"

namespace ccma {

std::vector<Wheel> DefaultWheels() {
  std::vector<Wheel> wheels(3);
  for (int i = 0; i < 3; ++i) wheels[i].angle = 2.0 * M_PI * i / 3.0;
  return wheels;
}

OmniWheelKinematics::OmniWheelKinematics(std::vector<Wheel> wheels) : wheels_(std::move(wheels)) {
  const int n = static_cast<int>(wheels_.size());
  if (n < 3) throw std::invalid_argument("an omni base needs at least 3 wheels");
  inverse_.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const Wheel& w = wheels_[i];
    if (!(w.radius > 0)) throw std::invalid_argument("wheel radius must be positive");
    if (!(std::abs(w.roller) < M_PI / 2)) throw std::invalid_argument("|roller angle| must be < pi/2");
    if (!(w.distance >= 0)) throw std::invalid_argument("wheel distance must not be negative");
    const double delta = w.angle + M_PI / 2 + w.mounting + w.roller;
    const Eigen::Vector2d e(std::cos(delta), std::sin(delta));
    const Eigen::Vector2d p(w.distance * std::cos(w.angle), w.distance * std::sin(w.angle));
    // e . (v + omega x p) = e_x v_x + e_y v_y + omega (e_y p_x - e_x p_y)
    const double scale = 1.0 / (w.radius * std::cos(w.roller));
    inverse_.row(i) << scale * e.x(), scale * e.y(), scale * (e.y() * p.x() - e.x() * p.y());
  }
  // Eigen's pseudoInverse() is exactly this solve against the identity, and
  // the decomposition's rank is that of its column-pivoting QR.
  const MinimumNormSolver cod(inverse_);
  if (cod.rank() < 3) throw std::invalid_argument("the wheel layout cannot produce every base twist");
  forward_ = cod.solveMatrix(Eigen::MatrixXd::Identity(n, n));
}

Eigen::VectorXd OmniWheelKinematics::WheelSpeeds(const Eigen::Vector3d& twist_B) const {
  return inverse_ * twist_B;
}

Eigen::Vector3d OmniWheelKinematics::Twist(const Eigen::VectorXd& wheel_speeds) const {
  return forward_ * wheel_speeds;
}

}  // namespace ccma
