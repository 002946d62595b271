"""Control step (paper Section III-B): the inverse question. Where must the
robots go so that the end-effector reaches a target? ccma minimises
1/2 |X_EE(u) - X*|^2 + lambda E over the effective controls u, with
gradients from the implicit-function sensitivities ds/du.

    PYTHONPATH=build/python python3 examples/python/control_step.py [MODEL.yaml]

(default models/4dof_reduced.yaml). Units: metres and radians. Prints
"example: ok" at the end when the target was reached; exit 1 when it was
not, 2 for a bad model file.
"""
import sys

import numpy as np

import ccma

np.set_printoptions(suppress=True, linewidth=120)


def main(path):
    try:
        model = ccma.load_model(path)
    except ccma.ModelError as e:
        print(e, file=sys.stderr)
        return 2
    control = ccma.ControlProblem(model)  # starts assembled at home; default options (LM)

    # The target: the current pose [x, y, z (m), roll, pitch, yaw (rad)] moved
    # 2 cm along y and 3 cm up. Only the components listed in the model's
    # `end_effector.controlled` are aimed at; the others are left to follow.
    target = control.current_pose + [0, 0.02, 0.03, 0, 0, 0]

    # move_to walks there in paper-size steps (at most 10 mm and 0.005 rad
    # each), each step warm-started from the last.
    r = control.move_to(target)
    print("converged %s in %d steps, %d iterations; error %.3g m; E = %.3g m^2"
          % (r.converged, r.steps, r.iterations, r.error, r.residual_energy))
    # The controls found: 3 per base [x m, y m, theta rad], then the motors.
    print("controls:", np.round(r.controls, 6) + 0.0)  # + 0.0: -0 shown as 0

    # The sensitivities at the solution. Their columns are the *effective*
    # controls: those the solver may change (a `reduced` base keeps its theta).
    print("effective controls (indices into the controls):", control.effective_controls)
    # ds/du: how the state (6 per body: rotation [rad], translation [m]) moves
    # per unit of each effective control.
    ds_du = control.state_sensitivity()
    # dX/du = dX/ds @ ds/du: how the end-effector moves per unit of each
    # effective control; rows x y z [m], then the rotation increment [rad].
    # This is the Jacobian the control step inverts.
    dX_du = control.end_effector_jacobian()
    print("ds/du:", ds_du.shape, "(state size %d x effective controls %d)"
          % (model.state_size, len(control.effective_controls)))
    print("dX/du:", dX_du.shape, "(rows x y z [m/unit], rx ry rz [rad/unit])")
    print(np.round(dX_du, 4) + 0.0)

    # The example's own checks: target reached, sensitivities of the right shape.
    if not r.converged:
        print("example: target not reached:", r.warning, file=sys.stderr)
        return 1
    n = len(control.effective_controls)
    if ds_du.shape != (model.state_size, n) or dX_du.shape != (6, n) or not np.isfinite(dX_du).all():
        print("example: unexpected sensitivity shapes", file=sys.stderr)
        return 1
    print("example: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "models/4dof_reduced.yaml"))
