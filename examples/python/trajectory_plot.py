"""Trajectory with a plot: follow the paper's sequential path on 4dof_reduced,
write one CSV row per control step and plot targets and reached positions
over time with Matplotlib.

    PYTHONPATH=build/python python3 examples/python/trajectory_plot.py \\
        models/4dof_reduced.yaml models/paths/4dof_sequential.csv OUT_DIR

Writes OUT_DIR/trajectory.csv and OUT_DIR/trajectory.png; prints
"example: ok" when every waypoint was reached.
"""
import os
import sys

import numpy as np

import ccma


def main(model_path, waypoints_path, out_dir):
    model = ccma.load_model(model_path)
    waypoints = ccma.load_waypoints(waypoints_path)  # raises ccma.WaypointError("file:line: ...")
    control = ccma.ControlProblem(model)
    path = control.follow(waypoints)  # arrays, one row per control step
    print("converged %s: %d steps, max error %.3g m, max E %.3g m^2, %.1f ms"
          % (path.converged, path.steps, path.max_error, path.max_residual_energy, path.solve_time_ms))

    os.makedirs(out_dir, exist_ok=True)
    csv_path = os.path.join(out_dir, "trajectory.csv")
    table = np.column_stack([path.time, path.targets[:, :3], path.reached[:, :3], path.controls])
    header = ["time_s", "target_x_m", "target_y_m", "target_z_m", "x_m", "y_m", "z_m"]
    header += ["u%d_%s" % (k, c) for k in range(model.num_bases) for c in ("x_m", "y_m", "theta_rad")]
    header += ["u_%s" % j.name for j in model.joints if j.actuated]
    np.savetxt(csv_path, table, delimiter=",", header=",".join(header), comments="", fmt="%.12g")
    print("wrote", csv_path)

    import matplotlib
    matplotlib.use("Agg")  # files only, no display
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(10, 7))
    for i, name in enumerate("xyz"):
        axes[i].plot(path.time, path.targets[:, i], "--", lw=2, label="target " + name)
        axes[i].plot(path.time, path.reached[:, i], lw=1, label="reached " + name)
        axes[i].set_ylabel(name + " [m]")
        axes[i].grid(True)
        axes[i].legend(loc="upper right")
    axes[2].set_xlabel("time [s]")
    fig.suptitle("ccma: end-effector along the 4-DOF sequential path")
    png_path = os.path.join(out_dir, "trajectory.png")
    fig.savefig(png_path, dpi=100)
    print("wrote", png_path)
    if not path.converged:
        print("example:", path.warning, file=sys.stderr)
        return 1
    print("example: ok")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        print("usage: trajectory_plot.py MODEL.yaml WAYPOINTS.csv OUT_DIR", file=sys.stderr)
        sys.exit(2)
    sys.exit(main(*sys.argv[1:]))
