// Swedish / omni wheel kinematics of a mobile base (Siegwart, Nourbakhsh and
// Scaramuzza, Introduction to Autonomous Mobile Robots, Section 3.2).
//
// Wheel i sits at p_i = distance * (cos angle, sin angle) in the base frame B
// (x along the heading). It drives along d_i = (cos delta, sin delta), delta =
// angle + pi/2 + mounting (mounting = 0: tangential, the usual omni base),
// and its rollers let it slide freely except along e_i, d_i turned by the
// roller angle gamma (0: omni wheel with rollers at 90 degrees; pi/4: mecanum):
//   radius * cos(gamma) * phi_dot_i = e_i . (v_B + omega x p_i)
// with the base twist (v_Bx [m/s], v_By [m/s], omega [rad/s]) in B and the
// wheel speeds phi_dot [rad/s].
#ifndef CCMA_OMNI_WHEELS_H_
#define CCMA_OMNI_WHEELS_H_

#include <vector>

#include <Eigen/Core>

namespace ccma {

struct Wheel {
  double angle = 0;     // rad, position of the wheel around the base centre
  double distance = 0.1;  // m, from the base centre
  double radius = 0.03;   // m
  double mounting = 0;  // rad, drive direction offset from tangential
  double roller = 0;    // rad, roller angle gamma (|gamma| < pi/2)
};

// Three omni wheels at 0, 120 and 240 degrees, 0.1 m out, radius 0.03 m: the
// default when a base has no `wheels:` block.
std::vector<Wheel> DefaultWheels();

class OmniWheelKinematics {
 public:
  // Throws std::invalid_argument for fewer than 3 wheels, a non-positive
  // radius, |roller| >= pi/2 or a layout that cannot produce every twist.
  explicit OmniWheelKinematics(std::vector<Wheel> wheels);

  // Inverse kinematics: wheel speeds [rad/s] for a base twist in B.
  Eigen::VectorXd WheelSpeeds(const Eigen::Vector3d& twist_B) const;
  // Forward kinematics: the base twist (least squares over the wheels, exact
  // when the speeds are consistent) for wheel speeds [rad/s].
  Eigen::Vector3d Twist(const Eigen::VectorXd& wheel_speeds) const;
  int num_wheels() const { return static_cast<int>(wheels_.size()); }
  const std::vector<Wheel>& wheels() const { return wheels_; }

 private:
  std::vector<Wheel> wheels_;
  Eigen::MatrixXd inverse_;  // n x 3: twist -> wheel speeds
  Eigen::MatrixXd forward_;  // 3 x n: its pseudo-inverse
};

}  // namespace ccma

#endif  // CCMA_OMNI_WHEELS_H_
