"""Trajectory with a plot: follow a waypoint file (by default the paper's
sequential path, its Fig. 7: y, z, x, then yaw, out and back), write the CSV
of `ccma trajectory` (one row per control step) and plot targets, reached
poses and the bases' paths with Matplotlib.

    PYTHONPATH=build/python python3 examples/python/trajectory_plot.py \\
        [MODEL.yaml WAYPOINTS.csv [OUT_DIR]]

Defaults: models/4dof_reduced.yaml, models/paths/4dof_sequential.csv,
trajectory_out/. Writes OUT_DIR/trajectory.csv and OUT_DIR/trajectory.png.
Units: s, m, rad. Prints "example: ok" at the end when every waypoint was
reached and the files were written; exit 1 otherwise, 2 for bad input files.
Without Matplotlib the plot is skipped with a message on stderr.
"""
import importlib.util
import os
import sys

import ccma


def plot(model, path, waypoints_name, png_path):
    """Writes the figure to png_path (Matplotlib without a display)."""
    import matplotlib
    matplotlib.use("Agg")  # write files only, no window
    import matplotlib.pyplot as plt

    # The columns of the CSV, by their header names (time_s, target_x_m, x_m, u0_x_m, ...).
    t = path.table
    time = t["time_s"]
    # Left: the end-effector over time (target dashed, reached solid).
    # Right: seen from above, the bases' paths on the ground and the end-effector's.
    fig = plt.figure(figsize=(13, 8), layout="constrained")
    grid = fig.add_gridspec(3, 2, width_ratios=[1.5, 1])
    ax_xy = fig.add_subplot(grid[0, 0])
    ax_z = fig.add_subplot(grid[1, 0], sharex=ax_xy)
    ax_yaw = fig.add_subplot(grid[2, 0], sharex=ax_xy)
    ax_top = fig.add_subplot(grid[:, 1])
    for ax, name, color in ((ax_xy, "x_m", "tab:blue"), (ax_xy, "y_m", "tab:orange"), (ax_z, "z_m", "tab:green"),
                            (ax_yaw, "yaw_rad", "tab:purple")):
        ax.plot(time, t["target_" + name], "--", color=color, lw=2.5, alpha=0.5, label="target_" + name)
        ax.plot(time, t[name], "-", color=color, lw=1, label=name + " (reached)")
    for ax, label in ((ax_xy, "end-effector x, y [m]"), (ax_z, "end-effector z [m]"),
                      (ax_yaw, "end-effector yaw [rad]")):
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.4)
        ax.legend(loc="best", fontsize=8)
    ax_yaw.set_xlabel("time [s]")
    ax_xy.set_title("end-effector: target (dashed) and reached (solid)")

    for k, base in enumerate(model.mobile_bases):
        x, y = t["u%d_x_m" % k], t["u%d_y_m" % k]
        line, = ax_top.plot(x, y, lw=2, label=base.name)
        ax_top.plot(x[0], y[0], "o", color=line.get_color(), mfc="none", ms=8)
    ax_top.plot(t["target_x_m"], t["target_y_m"], "k--", lw=2.5, alpha=0.4, label="end-effector target")
    ax_top.plot(t["x_m"], t["y_m"], "k-", lw=1, label="end-effector reached")
    ax_top.set_aspect("equal", adjustable="datalim")
    ax_top.set_xlabel("x [m]")
    ax_top.set_ylabel("y [m]")
    ax_top.set_title("seen from above (circle: start)")
    ax_top.grid(True, alpha=0.4)
    ax_top.legend(loc="best", fontsize=8)
    fig.suptitle("%s following %s: %d control steps, max error %.2g m"
                 % (model.name, waypoints_name, path.steps, path.max_error))
    fig.savefig(png_path, dpi=100)
    plt.close(fig)


def main(model_path, waypoints_path, out_dir):
    try:
        model = ccma.load_model(model_path)
        # Waypoints: rows time [s], x y z [m], roll pitch yaw [rad] (docs/waypoints.md).
        waypoints = ccma.load_waypoints(waypoints_path)
    except (ccma.ModelError, ccma.WaypointError) as e:
        print(e, file=sys.stderr)
        return 2
    control = ccma.ControlProblem(model)
    # follow() is `ccma trajectory`: it walks from waypoint to waypoint in small
    # control steps (10 mm, 0.005 rad); the result's attributes are the command's
    # JSON, and out= writes its CSV (one row per step; `ccma view --trajectory` reads it).
    os.makedirs(out_dir, exist_ok=True)
    csv_path = os.path.join(out_dir, "trajectory.csv")
    path = control.follow(waypoints, out=csv_path)
    print("converged %s: %d steps, max error %.3g m, max E %.3g m^2, %.1f ms"
          % (path.converged, path.steps, path.max_error, path.max_residual_energy, path.solve_time_ms))
    print("wrote", path.out, "(%d rows: %s, ...)" % (len(path.table), ", ".join(path.table.names[:4])))

    # The plot needs Matplotlib (Debian: python3-matplotlib); without it, only the CSV.
    png_path = os.path.join(out_dir, "trajectory.png")
    if importlib.util.find_spec("matplotlib") is None:
        png_path = None
        print("example: matplotlib is not installed: plot skipped (apt-get install python3-matplotlib)",
              file=sys.stderr)
    else:
        plot(model, path, os.path.basename(waypoints_path), png_path)
        print("wrote", png_path)

    # The example's own checks: every waypoint reached, both files written.
    if not path.converged:
        print("example: not every waypoint reached:", path.warning, file=sys.stderr)
        return 1
    if len(path.table) != path.steps or not path.table["reached"].all() or \
            (png_path and os.path.getsize(png_path) == 0):
        print("example: outputs incomplete", file=sys.stderr)
        return 1
    print("example: ok")
    return 0


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) not in (0, 2, 3):
        print("usage: trajectory_plot.py [MODEL.yaml WAYPOINTS.csv [OUT_DIR]]", file=sys.stderr)
        sys.exit(2)
    defaults = ["models/4dof_reduced.yaml", "models/paths/4dof_sequential.csv", "trajectory_out"]
    sys.exit(main(*(args + defaults[len(args):])))
