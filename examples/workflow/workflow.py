"""The path of examples/workflow/run.sh in Python (docs/workflow.md).

The five-bar linkage of the example-parallel-robots collection, imported with capsules on its
links, checked, driven, kept clear of a ledge, planned, loaded, redesigned, viewed, exported
and imported again: each stage by the call that is the command ([docs/python.md](python.md),
"Results: one name per concept"), printing the script's line, and asserting that its result
equals the command's JSON that run.sh kept (key by key, numbers within 1e-9 relative) where
the stage is deterministic. The inputs (waypoints, obstacles, design targets) are written
here from Python's own home pose and must equal the script's byte for byte.

Usage: workflow.py CLI_OUT_DIR [OUT_DIR]
  CLI_OUT_DIR  the folder run.sh wrote (default build/workflow)
  OUT_DIR      where this writes (default build/workflow_python; replaced)
Prints "workflow: ok" last; a failed check raises AssertionError naming the stage.
"""
import math
import os
import shutil
import sys

import ccma

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ROBOT = os.path.join(ROOT, "models", "robots", "example-parallel-robots", "5bar_linkage")
RADIUS = 0.02  # m, as run.sh
# Keys that name files the two runs wrote in their own folders, or measure time: not compared
# (export's `closures` is a path, import's a count, which is compared).
UNCOMPARED = {"out", "solve_time_ms"}


def same(stage, python, cli, path=""):
    """Asserts the Python result's JSON equals the command's: the same keys, numbers within
    1e-9 relative (1e-12 absolute near zero, where both are rounding)."""
    if isinstance(cli, dict):
        assert isinstance(python, dict), f"{stage}: {path} is {python!r}, the CLI's an object"
        keys = (set(cli) | set(python)) - UNCOMPARED
        missing = keys - set(python) or keys - set(cli)
        assert not missing, f"{stage}: {path} keys differ: {sorted(missing)}"
        for key in sorted(keys):
            if key == "closures" and isinstance(cli[key], str):
                assert os.path.basename(python[key]) == os.path.basename(cli[key]), f"{stage}: {path}.closures"
                continue
            same(stage, python[key], cli[key], f"{path}.{key}")
    elif isinstance(cli, list):
        assert len(python) == len(cli), f"{stage}: {path} has {len(python)} entries, the CLI's {len(cli)}"
        for i, (a, b) in enumerate(zip(python, cli)):
            same(stage, a, b, f"{path}[{i}]")
    elif isinstance(cli, bool) or isinstance(cli, str) or cli is None:
        assert python == cli, f"{stage}: {path} is {python!r}, the CLI's {cli!r}"
    else:
        assert abs(python - cli) <= 1e-9 * max(abs(python), abs(cli)) + 1e-12, \
            f"{stage}: {path} is {python!r}, the CLI's {cli!r}"


class Cli:
    """The JSON documents run.sh kept, by file name."""

    def __init__(self, folder):
        self.folder = folder

    def __call__(self, name):
        import json
        with open(os.path.join(self.folder, name)) as f:
            return json.load(f)

    def text(self, name):
        with open(os.path.join(self.folder, name)) as f:
            return f.read()


def write_inputs(home):
    """path.csv, obstacles.yaml, targets.csv exactly as run.sh writes them."""
    x0, y0, z0 = home
    rows = [(0, y0, z0), (2, y0 + 0.06, z0 + 0.03), (4, y0 + 0.06, z0 + 0.10), (6, y0, z0 + 0.10), (8, y0, z0)]
    with open("path.csv", "w") as f:
        f.write("# A loop in the five-bar's y-z plane (x is not controlled). Units: s, m, rad.\n")
        f.write("time,x,y,z,roll,pitch,yaw\n")
        for t, y, z in rows:
            f.write(f"{t},{x0!r},{y!r},{z!r},0,0,0\n")
    with open("obstacles.yaml", "w") as f:
        f.write("# A ledge under the five-bar's end-effector: its top 4.5 cm below the lowest point.\n")
        f.write("obstacles:\n")
        f.write(f"  - {{name: ledge, box: {{center: [{x0!r}, {y0 + 0.04!r}, {z0 - 0.07!r}], size: [0.4, 0.1, 0.05], "
                "yaw: 0}}\n")
    with open("targets.csv", "w") as f:
        f.write("# Two poses the design must reach with a margin of 0.05 (smallest singular value of dX/du).\n")
        f.write("time,x,y,z,roll,pitch,yaw\n")
        f.write(f"0,{x0!r},{y0!r},{z0 + 0.02!r},0,0,0\n1,{x0!r},{y0!r},{z0 - 0.013!r},0,0,0\n")


def import_and_check(cli):
    imported = ccma.import_robot(os.path.join(ROBOT, "robot.urdf"), closures=os.path.join(ROBOT, "robot.yaml"),
                                 end_effector="effector", collision_radius=RADIUS, out="5bar.yaml")
    assert imported.assembled and list(imported.controlled) == ["y", "z"], "import: not the planar five-bar"
    same("import", imported.to_dict(), cli("01_import.json"))
    print(f"import:     {imported.bodies} bodies, {imported.joints} joints, {imported.closures} closure, controlled "
          f"{','.join(imported.controlled)}, E at home {imported.residual_energy:.1e} m^2, "
          f"{imported.collision_capsules} capsules, {imported.collision_ignored_pairs} pairs touching at home ignored")
    model = imported.new_model
    check = ccma.check(model)
    assert check.assembled_at_home and check.end_effector_dof == 2, "check: expected 2 end-effector DOF"
    same("check", check.to_dict(), cli("02_check.json"))
    home = ccma.ForwardProblem(model).assemble([0.0, 0.0])
    same("check", home.to_dict(), cli("02_home.json"))
    p = home.end_effector.position
    print(f"check:      {check.controls} controls, {check.end_effector_dof} end-effector DOF, "
          f"{check.dof_with_controls_fixed} idle motion, clearance at home {check.clearance.min:.4f} m "
          f"({'|'.join(check.clearance.pair)}), end-effector y z {p[1]:.4f} {p[2]:.4f} m")
    write_inputs([float(v) for v in p])
    for name in ("path.csv", "obstacles.yaml", "targets.csv"):
        assert open(name).read() == cli.text(name), f"inputs: {name} differs from run.sh's"
    return model, [float(v) for v in p]


def drive(cli, model, home):
    _, y0, z0 = home
    control = ccma.ControlProblem(model).move_to([y0 + 0.06, z0 + 0.04])
    assert control.converged, control.warning
    same("control", control.to_dict(), cli("03_control.json"))
    u = control.controls
    print(f"control:    converged, error {control.error:.1e} m, controls {u[0]:.6f} {u[1]:.6f} rad, "
          f"{control.steps} path steps")
    waypoints = ccma.load_waypoints("path.csv")
    trajectory = ccma.ControlProblem(model).follow(waypoints, out="trajectory.csv")
    assert trajectory.converged, trajectory.warning
    same("trajectory", trajectory.to_dict(), cli("04_trajectory.json"))
    print(f"trajectory: {trajectory.waypoints} waypoints reached in {trajectory.steps} steps, largest error "
          f"{trajectory.max_error:.1e} m, smallest singular value of dX/du "
          f"{trajectory.conditioning.min_singular_value_dX_du_on_path:.4f}")
    return [float(v) for v in u], waypoints, trajectory.table


def obstacles_and_plan(cli, home, waypoints):
    _, y0, z0 = home
    with_ledge = ccma.load_model("5bar.yaml", obstacles="obstacles.yaml")
    walked = ccma.ControlProblem(with_ledge).follow(waypoints, out="trajectory_obstacles.csv")
    c = walked.clearance
    assert walked.converged and c.min_on_path >= c.margin and "ledge" in c.pair_on_path, "obstacles: the loop"
    same("obstacles", walked.to_dict(), cli("05_obstacles.json"))
    print(f"obstacles:  {walked.steps} steps, closest {c.min_on_path:.4f} m ({'|'.join(c.pair_on_path)}), "
          f"margin {c.margin} m")
    low = [y0, z0 - 0.013]
    free = ccma.ControlProblem(ccma.load_model("5bar.yaml")).move_to(low)
    stop = ccma.ControlProblem(with_ledge).move_to(low)
    z_stop = z0 - 0.045 + 0.04
    z = stop.end_effector.position[2]
    assert free.converged and not stop.converged and "'ledge'" in stop.warning, "obstacles: the stop"
    assert abs(z - z_stop) < 1e-9 and abs(stop.clearance.min - 0.02) < 1e-9, f"obstacles: stopped at z {z}"
    same("obstacles", free.to_dict(), cli("05_free.json"))
    same("obstacles", stop.to_dict(), cli("05_stop.json"))
    print(f"obstacles:  control to 1.3 cm below home stops {z - z_stop:.1e} m from the closed form, at clearance "
          f"{stop.clearance.min:.6f} m ({'|'.join(stop.clearance.pair)})")
    plan = ccma.plan(ccma.ControlProblem(with_ledge), waypoints, out="plan.csv")
    assert plan.converged and plan.clearance.min_on_path >= plan.clearance.margin, plan.warning
    same("plan", plan.to_dict(), cli("06_plan.json"))
    print(f"plan:       used {plan.used}, {plan.plan.reached_waypoints}/{plan.waypoints} waypoints, {plan.steps} steps, "
          f"{plan.iterations} iterations, closest {plan.clearance.min_on_path:.4f} m")
    return with_ledge


def statics_and_design(cli, model, u):
    forward = ccma.ForwardProblem(model)
    forward.assemble(u)
    statics = ccma.statics(forward, wrench=[0, -5, -20, 0, 0, 0])
    assert statics.assembled and statics.balanced, statics.warning
    same("statics", statics.to_dict(), cli("07_statics.json"))
    # effort = -F . dp/du: central differences of the assembled end-effector point.
    force, h = [0.0, -5.0, -20.0], 1e-6
    for k in range(2):
        ends = []
        for sign in (1, -1):
            v = list(u)
            v[k] += sign * h
            ends.append(ccma.ForwardProblem(model).assemble(v).end_effector.position)
        work = -sum(force[i] * (ends[0][i] - ends[1][i]) / (2 * h) for i in range(3))
        effort = statics.actuators[k].effort
        assert abs(work - effort) <= 1e-5 * max(1.0, abs(effort)), f"statics: effort {effort} != virtual work {work}"
    efforts = [a.effort for a in statics.actuators]
    print(f"statics:    efforts {efforts[0]:.4f} {efforts[1]:.4f} N*m (= -F . dp/du by central differences), "
          f"balanced, determinate {str(statics.determinate).lower()}")
    design = ccma.design("5bar.yaml", "targets.csv", vary_length=["mot1:free1", "mot2:free2"], min_singular_value=0.05,
                         out="5bar_designed.yaml")
    assert design.converged, design.warning
    same("design", design.to_dict(), cli("08_design.json"))
    changed = ", ".join(f"{c.parameter} {c.old:.4f} -> {c.new:.4f} m" for c in design.changed)
    margin = min(t.min_singular_value for t in design.targets)
    print(f"design:     converged in {design.iterations} iterations, {changed}, smallest singular value {margin:.4f}")
    with open("5bar_designed.yaml") as ours, open(os.path.join(cli.folder, "5bar_designed.yaml")) as theirs:
        assert ours.read() == theirs.read(), "design: the written model differs from the command's"


def view_export_reimport(cli, with_ledge, model):
    view = ccma.view(with_ledge, trajectory="plan.csv", out="5bar.html")
    assert view.flagged_frames == 0, "view: frames flagged"
    same("view", view.to_dict(), cli("09_view.json"))
    print(f"view:       5bar.html, {view.frames} frames, none flagged")
    urdf = ccma.export(model, "urdf", "5bar.urdf")
    sdf = ccma.export(model, "sdf", "5bar.sdf")
    same("export", urdf.to_dict(), cli("10_export_urdf.json"))
    same("export", sdf.to_dict(), cli("10_export_sdf.json"))
    for name in ("5bar.urdf", "5bar.closures.yaml", "5bar.sdf"):
        assert open(name).read() == cli.text(name), f"export: {name} differs from the command's"
    print(f"export:     5bar.urdf ({urdf.links} links, {urdf.loops} closure in {os.path.basename(urdf.closures)}), "
          f"5bar.sdf ({sdf.links} links, {sdf.loops} loop)")
    again = [ccma.import_robot("5bar.urdf", closures="5bar.closures.yaml", collision_radius=RADIUS,
                               out="5bar_from_urdf.yaml"),
             ccma.import_robot("5bar.sdf", collision_radius=RADIUS, out="5bar_from_sdf.yaml")]
    same("reimport", again[0].to_dict(), cli("11_reimport_urdf.json"))
    same("reimport", again[1].to_dict(), cli("11_reimport_sdf.json"))
    return [model] + [a.new_model for a in again]


def compare_round_trip(cli, models, u, table):
    """Home, the control stage's controls and every 8th step of the trajectory, as run.sh."""
    controls = [[0.0, 0.0], list(u)] + [[float(table["u_mot1_rad"][r]), float(table["u_mot2_rad"][r])]
                                        for r in range(0, len(table), 8)]
    worst = 0.0
    for i, v in enumerate(controls):
        poses = [ccma.ForwardProblem(m).assemble(v) for m in models]
        for m, pose in zip(("5bar", "5bar_from_urdf", "5bar_from_sdf"), poses):
            assert pose.assembled, f"reimport: {m} not assembled at {v}"
            same("reimport", pose.to_dict(), cli(f"12_{m}_{i}.json"))
        for pose in poses[1:]:
            a, b = pose.end_effector, poses[0].end_effector
            worst = max(worst, math.dist(a.position, b.position),
                        max(abs(x - y) for ra, rb in zip(a.rotation, b.rotation) for x, y in zip(ra, rb)))
    assert worst < 1e-9, f"reimport: the re-imported models differ by {worst}"
    print(f"reimport:   URDF and SDFormat re-imports give the same end-effector pose at {len(controls)} controls "
          f"(largest difference {worst:.1e})")


def main():
    cli = Cli(os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "workflow")))
    out = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "build", "workflow_python"))
    assert os.path.isfile(os.path.join(cli.folder, "12_5bar_0.json")), f"run examples/workflow/run.sh first ({cli.folder})"
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    os.chdir(out)
    model, home = import_and_check(cli)
    u, waypoints, table = drive(cli, model, home)
    with_ledge = obstacles_and_plan(cli, home, waypoints)
    statics_and_design(cli, model, u)
    models = view_export_reimport(cli, with_ledge, model)
    compare_round_trip(cli, models, u, table)
    print(f"outputs: {out}")
    print("workflow: ok")


if __name__ == "__main__":
    main()
