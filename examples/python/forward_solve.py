"""Forward solve: load a model, move its bases a little, assemble the
mechanism there and print what a simulation loop would read.

    PYTHONPATH=build/python python3 examples/python/forward_solve.py models/4dof_reduced.yaml

Prints "example: ok" when the mechanism assembled (exit 1 otherwise).
"""
import sys

import ccma


def main(path):
    model = ccma.load_model(path)           # raises ccma.ModelError("file:line: key: ...")
    forward = ccma.ForwardProblem(model)    # keeps the model alive

    # Controls: 3 per mobile base (x [m], y [m], theta [rad]), then one per
    # actuated joint. Translating every base by the same amount moves the
    # whole mechanism rigidly, so these controls are reachable for any model.
    u = model.home_controls
    for k in range(model.num_bases):
        u[3 * k] += 0.02      # +2 cm along x
        u[3 * k + 1] -= 0.01  # -1 cm along y
    r = forward.assemble(u)  # small sub-steps: stays on the assembly branch
    print("assembled %s, E = %.3g m^2, %d iterations, %.3f ms"
          % (r.assembled, r.residual_energy, r.iterations, r.solve_time_ms))
    print("end-effector p_WE =", r.end_effector.position, "m, rpy =", r.end_effector.rpy, "rad")
    for pose in forward.body_poses()[:3]:
        print("body %s: p_WB = %s m" % (pose.name, pose.position))
    for j in forward.joint_coordinates():
        print("joint %s: q = %.6f" % (model.joints[j.joint].name, j.q))
    if not r.assembled:
        print("example: not assembled", file=sys.stderr)
        return 1
    print("example: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "models/4dof_reduced.yaml"))
