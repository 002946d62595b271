// Your own mechanism, written from scratch: two omni robots carry a beam on
// two legs, all hinges parallel to y, so the chain moves in the x-z plane.
//
//   side view (x to the right, z up; y points into the page):
//
//              knee_a o====== beam ======+ weld_b
//                    /  end-effector at   \ leg_b, welded
//             leg_a /   (0, 0, 0.6)        \ to the beam
//                  /                        \ (hinge axes: y)
//           hip_a o                          o hip_b
//            [robot_a]                    [robot_b]      ground, z = 0
//             x = -0.4                     x = 0.4
//
// Leg A is hinged on its robot and under the beam. With the robots standing
// still, leg A, the beam with leg B, and the ground between the hips form a
// triangle: rigid. Bringing the robots together lifts the beam. Every key is
// described in docs/model_format.md (section named next to each key below);
// docs/first_mechanism.md walks through designing such a model.
//
//   build/examples/example_my_mechanism
//
// Prints "example: ok" at the end when the model is rigid with its controls
// fixed, assembled at home, and a control step lifted the beam; exit 1
// otherwise.
#include <iostream>

#include <ccma/ccma.h>

namespace {

// Units: metres and radians. Every position, point and axis is in world
// coordinates at home, the pose the file describes (docs/model_format.md,
// "Conventions"); the loader converts them into each body's frame.
const char* kModel = R"(
# "Top-level keys": name (letters, digits, _ and -; see "Names") and a free-text description.
name: two_robot_lifter
description: "Two omni robots carry a beam on two legs in a vertical plane."

# "bodies": every rigid part that is not a robot; `position` is where its
# frame sits at home (here the middle of each part; `rpy` omitted = not turned).
bodies:
  - {name: beam,  position: [0, 0, 0.6]}
  - {name: leg_a, position: [-0.275, 0, 0.4]}
  - {name: leg_b, position: [0.275, 0, 0.4]}

# "mobile_bases": the robots. `type: omni` moves in any direction;
# `actuation: complete` lets the solver change x, y and the heading theta
# ("reduced" would hold theta); `pose: [x, y, theta]` at home (m, m, rad).
mobile_bases:
  - {name: robot_a, type: omni, actuation: complete, pose: [-0.4, 0, 0]}
  - {name: robot_b, type: omni, actuation: complete, pose: [0.4, 0, 0]}

# "joints": `type` (revolute = hinge about `axis`, fixed = weld), `between`
# the two bodies it connects, `point` where it is at home, `axis` for hinges;
# `name` is optional ("Joint names"). The hips sit 0.2 m up on the robots.
joints:
  - {name: hip_a,  type: revolute, between: [robot_a, leg_a], point: [-0.4, 0, 0.2], axis: [0, 1, 0]}
  - {name: knee_a, type: revolute, between: [leg_a, beam],    point: [-0.15, 0, 0.6], axis: [0, 1, 0]}
  - {name: weld_b, type: fixed,    between: [beam, leg_b],    point: [0.15, 0, 0.6]}
  - {name: hip_b,  type: revolute, between: [robot_b, leg_b], point: [0.4, 0, 0.2], axis: [0, 1, 0]}

# "end_effector": the point of `body` whose pose is controlled, and which of
# x y z roll pitch yaw the control solver aims at (the others follow).
end_effector:
  body: beam
  point: [0, 0, 0.6]
  controlled: [x, y, z]
)";

}  // namespace

int main() {
  try {
    // Validated like a file; errors read "two_robot_lifter.yaml:LINE: key: what".
    const ccma::Model model = ccma::LoadModelFromString(kModel, "two_robot_lifter.yaml");
    std::cout << std::boolalpha << model.name << ": " << model.num_bodies() << " bodies (with the robots), "
              << model.joints.size() << " joints, " << model.num_controls() << " controls\n";

    // Mobility at home (what `ccma check` prints). Counting alone (Grübler:
    // 3 bodies x 6 = 18 DOF, minus 3 hinges x 5 and a weld x 6 = 21) says
    // "over-constrained"; but with parallel hinges 3 of those constraints
    // repeat, and the rank of the constraint Jacobian gives the true numbers.
    const ccma::MobilityReport m =
        ccma::AnalyzeMobility(model, ccma::State::Home(model), model.home_controls());
    std::cout << "rigid_with_controls_fixed: " << m.rigid_with_controls_fixed
              << " (free motions with the robots still: " << m.dof_with_controls_fixed << ")\n"
              << "end_effector_dof: " << m.end_effector_dof
              << " (x, y, z and yaw; the beam's tilt follows its height)\n";

    // Assembled at home: every joint closed (E < 1e-16 m^2).
    ccma::ForwardProblem forward(model);
    const ccma::ForwardResult home = forward.Assemble(model.home_controls());
    std::cout << "assembled at home: " << home.assembled << " (E = " << home.residual_energy << " m^2)\n";

    // A control step: lift the beam's point 2 cm and shift it 1 cm along x.
    ccma::ControlProblem control(model);
    ccma::PoseTarget target = control.CurrentPose();
    target.position += Eigen::Vector3d(0.01, 0, 0.02);
    const ccma::ControlResult r = control.MoveTo(target);
    // Controls: [x_a, y_a, theta_a, x_b, y_b, theta_b] ("Controls").
    const Eigen::VectorXd& u = control.controls();
    const double gap = (u.segment<2>(3) - u.segment<2>(0)).norm();
    std::cout << "lift: converged " << r.converged << ", error " << r.error << " m; robots now " << gap
              << " m apart (were 0.8 m)\n";
    // The hinges' angles after the lift ("Joint coordinates"; rad, 0 at home).
    for (const ccma::JointCoordinateReport& j : ccma::JointCoordinates(model, control.forward().state())) {
      std::cout << "  " << model.joints[j.joint].name << ": q = " << j.q << " rad\n";
    }

    const bool ok = m.rigid_with_controls_fixed && m.end_effector_dof >= 3 && home.assembled && r.converged &&
                    gap < 0.8;
    if (!ok) {
      std::cerr << "example: unexpected result\n";
      return 1;
    }
    std::cout << "example: ok\n";
  } catch (const std::exception& e) {  // ccma::ModelError: the string is not a valid model
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
