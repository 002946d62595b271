"""Control step: find controls that move the end-effector 3 cm up and 2 cm
along y, then look at the sensitivities the solver used.

    PYTHONPATH=build/python python3 examples/python/control_step.py models/4dof_reduced.yaml

Prints "example: ok" when the target was reached (exit 1 otherwise).
"""
import sys

import numpy as np

import ccma


def main(path):
    model = ccma.load_model(path)
    control = ccma.ControlProblem(model)  # LM outer loop, implicit-function gradients

    # [x, y, z, roll, pitch, yaw] in m and rad; uncontrolled components are ignored.
    target = control.current_pose + [0, 0.02, 0.03, 0, 0, 0]
    r = control.move_to(target)  # paper-size steps (10 mm, 0.005 rad), warm-started
    print("converged %s in %d steps, %d iterations; error %.3g m; E = %.3g m^2"
          % (r.converged, r.steps, r.iterations, r.error, r.residual_energy))
    print("controls:", np.round(r.controls, 6))

    # ds/du: how the state moves per unit of each effective control; dX/du
    # (rows x y z [m], then the rotation increment [rad]) is what the control
    # step inverts.
    ds_du = control.state_sensitivity()
    dX_du = control.end_effector_jacobian()
    print("ds/du:", ds_du.shape, " dX/du:", dX_du.shape)
    print("dX/du position rows:\n", np.round(dX_du[:3], 4))
    if not r.converged:
        print("example:", r.warning, file=sys.stderr)
        return 1
    print("example: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "models/4dof_reduced.yaml"))
