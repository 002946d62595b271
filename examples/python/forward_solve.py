"""Forward solve (paper Section III-A): the robots stand somewhere, where are
all the links and the end-effector? ccma finds the configuration s that makes
every joint constraint hold, i.e. minimises E = 1/2 |C(s, u)|^2 for the
controls u; "assembled" means E < 1e-16 m^2 (all joints closed).

    PYTHONPATH=build/python python3 examples/python/forward_solve.py [MODEL.yaml]

(default models/4dof_reduced.yaml). Units everywhere: metres, radians; E in
m^2. Prints "example: ok" at the end when the mechanism assembled; exit 1 when
it did not, 2 for a bad model file.
"""
import sys

import numpy as np

import ccma

np.set_printoptions(suppress=True)  # 0.00924, not 9.24e-03


def tidy(v):
    """Rounded to 1e-6 (m or rad) for printing; -0 shown as 0."""
    return np.round(v, 6) + 0.0


def main(path):
    try:
        model = ccma.load_model(path)  # raises ccma.ModelError("file:line: key: ...")
    except ccma.ModelError as e:
        print(e, file=sys.stderr)
        return 2
    forward = ccma.ForwardProblem(model)  # keeps the model alive

    # The controls u: 3 per mobile base, in file order: x [m], y [m], theta [rad];
    # then one per actuated joint (its coordinate q, rad or m). Home = the file's poses.
    u = model.home_controls  # a NumPy copy: safe to modify

    # Move the bases a little: each one 1 cm towards the bases' centre. The
    # formation shrinks, so the legs fold and the end-effector rises.
    if model.num_bases:
        xy = np.array([u[3 * k:3 * k + 2] for k in range(model.num_bases)])
        for k, to_centre in enumerate(xy.mean(axis=0) - xy):
            if np.linalg.norm(to_centre) > 0:
                u[3 * k:3 * k + 2] += 0.01 * to_centre / np.linalg.norm(to_centre)
    # Motors (models such as stewart_gough_6ups have no bases): +0.01 rad or m each.
    for j in model.joints:
        if j.actuated:
            u[j.control] += 0.01

    # assemble() walks from the current controls to u in sub-steps of at most
    # 2 cm / 0.02 rad, warm-starting each solve, so it stays on the assembly
    # branch connected to home. (solve(u) does one warm-started solve.)
    r = forward.assemble(u)
    print("assembled %s, E = %.3g m^2, %d iterations in %d sub-steps, %.3f ms"
          % (r.assembled, r.residual_energy, r.iterations, r.substeps, r.solve_time_ms))

    # The end-effector: the model's `end_effector.point`; rpy is its rotation since home.
    ee = r.end_effector
    print("end-effector p_WE = %s m (moved by %s m), rpy = %s rad"
          % (tidy(ee.position), tidy(ee.position - model.end_effector.p_W_home), tidy(ee.rpy)))

    # Body poses: position p_WB [m] and orientation of each body's frame (file
    # order: `bodies` first, then the mobile bases). The first three:
    for pose in forward.body_poses()[:3]:
        print("body %s: p_WB = %s m, rpy = %s rad"
              % (pose.name, tidy(pose.position), tidy(pose.rpy)))
    # Joint coordinates q (0 at home): the angle of a revolute joint [rad], the
    # travel of a prismatic one [m]; other joint types have none.
    for j in forward.joint_coordinates():
        joint = model.joints[j.joint]
        q = 0.0 if abs(j.q) < 1e-9 else j.q  # rounding noise printed as 0
        print("joint %s: q = %.6f %s" % (joint.name, q, "m" if joint.type == "prismatic" else "rad"))

    if not r.assembled:
        # Not a crash: the solver reports the closest configuration it found. A
        # mechanism with fewer end-effector DOF than controls (`ccma check`)
        # cannot follow every base motion; 4dof_complete and hybrid_ccma cannot
        # follow this one.
        print("example: not assembled (E = %.3g m^2): these controls are not reachable for %s"
              % (r.residual_energy, model.name), file=sys.stderr)
        return 1
    print("example: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "models/4dof_reduced.yaml"))
