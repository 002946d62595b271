"""Your own mechanism, written from scratch: two omni robots carry a beam on
two legs in a vertical plane. Leg A is hinged on its robot and under the
beam; leg B is welded to the beam and hinged on its robot. Bringing the
robots together lifts the beam. Every key is described in
docs/model_format.md (and walked through in docs/first_mechanism.md).

    PYTHONPATH=build/python python3 examples/python/my_mechanism.py [--view]

Prints "example: ok" when the model is rigid with its controls fixed,
assembled at home, and a control step lifts the beam by 2 cm.
"""
import sys

import ccma

# Units: metres and radians; points and axes in world coordinates at home.
MODEL = """
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
"""


def main():
    # Validated like a file; errors name "two_robot_lifter.yaml:LINE: key".
    model = ccma.load_model_from_string(MODEL, "two_robot_lifter.yaml")
    m = ccma.analyze_mobility(model)  # at home
    print("rigid with controls fixed: %s, end-effector DOF: %d, E at home: %.3g m^2"
          % (m.rigid_with_controls_fixed, m.end_effector_dof, m.energy))
    home = ccma.ForwardProblem(model).assemble(model.home_controls)
    print("assembled at home:", home.assembled)

    control = ccma.ControlProblem(model)
    r = control.move_to(control.current_pose + [0.01, 0, 0.02, 0, 0, 0])  # lift 2 cm, 1 cm along x
    gap = r.controls[3] - r.controls[0]
    print("lift: converged %s, error %.3g m; robots now %.4f m apart (were 0.8 m)" % (r.converged, r.error, gap))
    if not (m.rigid_with_controls_fixed and home.assembled and r.converged and gap < 0.8):
        print("example: unexpected result", file=sys.stderr)
        return 1
    if "--view" in sys.argv:  # the 3D page of the new mechanism
        print("wrote", ccma.view(model, out="two_robot_lifter.html"))
    print("example: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
