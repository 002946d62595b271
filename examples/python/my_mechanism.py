r"""Your own mechanism, written from scratch: two omni robots carry a beam on
two legs, all hinges parallel to y, so the chain moves in the x-z plane.

  side view (x to the right, z up; y points into the page):

             knee_a o====== beam ======+ weld_b
                   /  end-effector at   \ leg_b, welded
            leg_a /   (0, 0, 0.6)        \ to the beam
                 /                        \ (hinge axes: y)
          hip_a o                          o hip_b
           [robot_a]                    [robot_b]      ground, z = 0
            x = -0.4                     x = 0.4

Leg A is hinged on its robot and under the beam. With the robots standing
still, leg A, the beam with leg B, and the ground between the hips form a
triangle: rigid. Bringing the robots together lifts the beam. Every key is
described in docs/model_format.md (section named next to each key below);
docs/first_mechanism.md walks through designing such a model.

    PYTHONPATH=build/python python3 examples/python/my_mechanism.py [--view]

(--view also writes two_robot_lifter.html, the 3D viewer.) Prints
"example: ok" at the end when the model is rigid with its controls fixed,
assembled at home, and a control step lifted the beam; exit 1 otherwise.
"""
import sys

import numpy as np

import ccma

# Units: metres and radians. Every position, point and axis is in world
# coordinates at home, the pose the file describes (docs/model_format.md,
# "Conventions"); the loader converts them into each body's frame.
MODEL = """
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
"""


def main():
    try:
        # Validated like a file; errors read "two_robot_lifter.yaml:LINE: key: what".
        model = ccma.load_model_from_string(MODEL, "two_robot_lifter.yaml")
    except ccma.ModelError as e:
        print(e, file=sys.stderr)
        return 1
    print("%s: %d bodies (with the robots), %d joints, %d controls"
          % (model.name, model.num_bodies, len(model.joints), model.num_controls))

    # Mobility at home (what `ccma check` prints). Counting alone (Gruebler:
    # 3 bodies x 6 = 18 DOF, minus 3 hinges x 5 and a weld x 6 = 21) says
    # "over-constrained"; but with parallel hinges 3 of those constraints
    # repeat, and the rank of the constraint Jacobian gives the true numbers.
    m = ccma.check(model)  # at home; m.to_dict() is the JSON of `ccma check`
    print("rigid_with_controls_fixed: %s (free motions with the robots still: %d)"
          % (m.rigid_with_controls_fixed, m.dof_with_controls_fixed))
    print("end_effector_dof: %d (x, y, z and yaw; the beam's tilt follows its height)" % m.end_effector_dof)

    # Assembled at home: every joint closed (E < 1e-16 m^2).
    home = ccma.ForwardProblem(model).assemble(model.home_controls)
    print("assembled at home: %s (E = %.3g m^2)" % (home.assembled, home.residual_energy))

    # A control step: lift the beam's point 2 cm and shift it 1 cm along x.
    control = ccma.ControlProblem(model)
    r = control.move_to(control.current_pose + [0.01, 0, 0.02, 0, 0, 0])
    # Controls: [x_a, y_a, theta_a, x_b, y_b, theta_b] ("Controls").
    gap = np.linalg.norm(r.controls[3:5] - r.controls[0:2])
    print("lift: converged %s, error %.3g m; robots now %.4f m apart (were 0.8 m)" % (r.converged, r.error, gap))
    # The hinges' angles after the lift ("Joint coordinates"; rad, 0 at home).
    for j in control.forward.joint_coordinates():
        print("  %s: q = %.6f rad" % (model.joints[j.joint].name, j.q))

    ok = (m.rigid_with_controls_fixed and m.end_effector_dof >= 3 and home.assembled and r.converged
          and gap < 0.8)
    if not ok:
        print("example: unexpected result", file=sys.stderr)
        return 1
    if "--view" in sys.argv:  # the 3D page of the new mechanism, opens offline in a browser
        print("wrote", ccma.view(model, out="two_robot_lifter.html").out)
    print("example: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
