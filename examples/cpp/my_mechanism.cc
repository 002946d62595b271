// Your own mechanism, written from scratch: two omni robots carry a beam on
// two legs in a vertical plane. Leg A is hinged on its robot and under the
// beam; leg B is welded to the beam and hinged on its robot. Bringing the
// robots together lifts the beam. Every key is described in
// docs/model_format.md (and walked through in docs/first_mechanism.md).
//   build/examples/example_my_mechanism
// Prints "example: ok" when the model is rigid with its controls fixed,
// assembled at home, and a control step lifts the beam by 2 cm.
#include <iostream>

#include <ccma/ccma.h>

namespace {

// Units: metres and radians; points and axes in world coordinates at home.
const char* kModel = R"(
name: two_robot_lifter
description: "Two omni robots carry a beam on two legs in a vertical plane."
bodies:                                   # rigid bodies; `position`: the body frame's origin at home
  - {name: beam,  position: [0, 0, 0.6]}
  - {name: leg_a, position: [-0.275, 0, 0.4]}
  - {name: leg_b, position: [0.275, 0, 0.4]}
mobile_bases:                             # the actuators: pose [x, y, theta] at home
  - {name: robot_a, type: omni, actuation: complete, pose: [-0.4, 0, 0]}
  - {name: robot_b, type: omni, actuation: complete, pose: [0.4, 0, 0]}
joints:                                   # `between: [A, B]`, the joint point (and axis) at home
  - {name: hip_a,  type: revolute, between: [robot_a, leg_a], point: [-0.4, 0, 0.2], axis: [0, 1, 0]}
  - {name: knee_a, type: revolute, between: [leg_a, beam],    point: [-0.15, 0, 0.6], axis: [0, 1, 0]}
  - {name: weld_b, type: fixed,    between: [beam, leg_b],    point: [0.15, 0, 0.6]}
  - {name: hip_b,  type: revolute, between: [robot_b, leg_b], point: [0.4, 0, 0.2], axis: [0, 1, 0]}
end_effector:                             # the point to control, and which components
  body: beam
  point: [0, 0, 0.6]
  controlled: [x, y, z]
)";

}  // namespace

int main() {
  try {
    // Validated like a file; errors name "two_robot_lifter.yaml:LINE: key".
    const ccma::Model model = ccma::LoadModelFromString(kModel, "two_robot_lifter.yaml");
    // Mobility at home: rigid when the robots stand still? How many
    // end-effector DOF can the robots drive?
    const ccma::MobilityReport m =
        ccma::AnalyzeMobility(model, ccma::State::Home(model), model.home_controls());
    std::cout << "rigid with controls fixed: " << m.rigid_with_controls_fixed
              << ", end-effector DOF: " << m.end_effector_dof << ", E at home: " << m.energy << " m^2\n";

    ccma::ForwardProblem forward(model);
    const ccma::ForwardResult home = forward.Assemble(model.home_controls());
    std::cout << "assembled at home: " << home.assembled << "\n";

    // Lift the beam 2 cm and shift it 1 cm along x.
    ccma::ControlProblem control(model);
    ccma::PoseTarget target = control.CurrentPose();
    target.position += Eigen::Vector3d(0.01, 0, 0.02);
    const ccma::ControlResult r = control.MoveTo(target);
    const Eigen::VectorXd& u = control.controls();
    std::cout << "lift: converged " << r.converged << ", error " << r.error << " m; robots now "
              << u[3] - u[0] << " m apart (were 0.8 m)\n";
    const bool ok = m.rigid_with_controls_fixed && home.assembled && r.converged && u[3] - u[0] < 0.8;
    if (!ok) {
      std::cerr << "example: unexpected result\n";
      return 1;
    }
    std::cout << "example: ok\n";
  } catch (const ccma::ModelError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
  return 0;
}
