"""Python agrees with the `ccma` command (issue 35, finding 6): on the same
inputs, every analysis's result has the command's JSON as to_dict(), key by key
(the same keys; flags as bool, arrays as lists; numbers within 1e-9 relative,
timing keys aside), its attributes are those keys with the same values, and a
result the command writes as CSV has the CSV's columns as its table (the same
names in the same order, flags as bool, empty cells as NaN)."""
import csv
import inspect
import math
import pathlib

import numpy as np
import pytest

import ccma
from conftest import MODELS, ROOT, csv_numbers, run_tool

PATHS = ROOT / "models" / "paths"
OBSTACLES = ROOT / "examples" / "obstacles"
STATICS = ROOT / "examples" / "statics"
MODEL_4DOF = str(ROOT / "models" / "4dof_reduced.yaml")

TIMING = {"solve_time_ms", "seconds"}
FILE_KEYS = {"out", "files", "plots", "plot_warning"}  # what the command wrote; Python names only its own files
REL, ABS = 1e-9, 1e-12


# ------------------------------------------------------------------ comparisons

def assert_same_json(py, cli, where="$", ignore=TIMING):
    """The JSON values agree: same keys, same types (bool, int, float, str, None,
    list, dict), strings and flags equal, numbers within REL (ABS near zero)."""
    if isinstance(cli, dict):
        assert isinstance(py, dict), "%s: %r is not an object" % (where, py)
        assert sorted(set(py) - ignore) == sorted(set(cli) - ignore), where
        for key in cli:
            if key not in ignore:
                assert_same_json(py[key], cli[key], where + "." + key, ignore)
    elif isinstance(cli, list):
        assert isinstance(py, list), "%s: %r is not a list" % (where, type(py))
        assert len(py) == len(cli), where
        for k, (a, b) in enumerate(zip(py, cli)):
            assert_same_json(a, b, "%s[%d]" % (where, k), ignore)
    elif isinstance(cli, float):
        assert type(py) is float, "%s: %r is not a float" % (where, py)
        assert math.isclose(py, cli, rel_tol=REL, abs_tol=ABS), "%s: %r != %r" % (where, py, cli)
    else:
        assert type(py) is type(cli), "%s: %r (%s) vs %r (%s)" % (where, py, type(py), cli, type(cli))
        assert py == cli, "%s: %r != %r" % (where, py, cli)


def plain(value):
    """An attribute as JSON: arrays as lists, records and poses as objects."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, ccma.Record):
        return value.to_dict()
    if isinstance(value, ccma.EndEffectorPose):
        return {"position": value.position.tolist(), "rotation": value.rotation.tolist(), "rpy": value.rpy.tolist()}
    if isinstance(value, ccma.BodyPose):
        return {"name": value.name, "position": value.position.tolist(), "rpy": value.rpy.tolist(),
                "quaternion": value.quaternion.tolist()}
    if isinstance(value, list):
        return [plain(v) for v in value]
    return value


def assert_agrees(result, cli, ignore=frozenset()):
    """result.to_dict() is the command's JSON, and each key is an attribute of that value."""
    document = result.to_dict()
    assert_same_json(document, cli, ignore=TIMING | FILE_KEYS | set(ignore))
    for key, value in document.items():
        if key in TIMING:
            continue
        assert_same_json(plain(getattr(result, key)), value, "attribute " + key)
    if hasattr(type(result), "json_keys"):
        assert set(document) <= set(type(result).json_keys()), "keys without a documented attribute"


def read_csv(path, comment_lines=0):
    with open(path, newline="") as f:
        rows = list(csv.reader(f.readlines()[comment_lines:]))
    return rows[0], rows[1:]


def assert_table_is_csv(table, path, comment_lines=0, rel=REL):
    """The table has the CSV's columns: names, order, rows, and each cell's value."""
    header, rows = read_csv(path, comment_lines)
    assert table.names == header
    assert len(table) == len(rows)
    for k, name in enumerate(header):
        if name in TIMING:  # a step's wall time
            continue
        column, cells = table[name], [row[k] for row in rows]
        if column.dtype == bool:
            assert cells and set(cells) <= {"0", "1"}, name
            assert column.tolist() == [c == "1" for c in cells], name
        elif column.dtype.kind == "i":
            assert column.tolist() == [int(c) for c in cells], name
        elif column.dtype == object:
            assert column.tolist() == cells, name
        else:
            for i, (v, c) in enumerate(zip(column.tolist(), cells)):
                if c == "":
                    assert math.isnan(v), "%s[%d]: the CSV leaves it empty, Python has %r" % (name, i, v)
                else:
                    assert math.isclose(v, float(c), rel_tol=rel, abs_tol=ABS), "%s[%d]: %r != %s" % (name, i, v, c)


def shifted_controls(model):
    """Every base 15 mm along x and 10 mm along y, actuated joints 0.01 in (reachable by every model)."""
    u = model.home_controls.copy()
    for k in range(model.num_bases):
        u[3 * k] += 0.015
        u[3 * k + 1] -= 0.010
    u[3 * model.num_bases:] += 0.01
    return u


# ------------------------------------------------------------------ check, simulate, control

def test_check_equals_cli(model_path):
    assert_agrees(ccma.check(ccma.load_model(model_path)), run_tool("check", "--model=" + model_path))


def test_check_with_an_obstacles_file_equals_cli():
    obstacles = str(OBSTACLES / "pillar_on_base2.yaml")
    cli = run_tool("check", "--model=" + MODEL_4DOF, "--obstacles=" + obstacles)
    result = ccma.check(ccma.load_model(MODEL_4DOF, obstacles=obstacles))
    assert_agrees(result, cli)
    assert result.clearance.pair == ["base2", "pillar"] and result.clearance["min"] > 0


def test_simulate_equals_cli(model_path):
    model = ccma.load_model(model_path)
    u = shifted_controls(model)
    cli = run_tool("simulate", "--model=" + model_path, "--controls=" + csv_numbers(u))
    result = ccma.ForwardProblem(model).assemble(u)
    assert_agrees(result, cli)
    assert result.start == "home"


def test_simulate_not_assembled_says_what_the_cli_says():
    model = ccma.load_model(MODEL_4DOF)
    u = model.home_controls.copy()
    u[1] += 0.05  # one base alone 5 cm along y: the chain cannot follow
    cli = run_tool("simulate", "--model=" + MODEL_4DOF, "--controls=" + csv_numbers(u))
    result = ccma.ForwardProblem(model).assemble(u)
    assert not result.assembled and result.warning.startswith("not assembled")
    assert_agrees(result, cli)


def control_target(model):
    p = model.end_effector.p_W_home
    return [p[0], p[1] + 0.01, p[2] + 0.02, 0.0, 0.0, 0.0]


def test_control_equals_cli(model_path):
    model = ccma.load_model(model_path)
    target = control_target(model)
    cli = run_tool("control", "--model=" + model_path, "--target=" + csv_numbers(target))
    assert_agrees(ccma.ControlProblem(model).move_to(target), cli)


def test_control_with_options_and_a_secondary_objective_equals_cli():
    model = ccma.load_model(MODEL_4DOF)
    target = [0.02, 0.05, 0.62, 0, 0, 0.1]
    cli = run_tool("control", "--model=" + MODEL_4DOF, "--target=" + csv_numbers(target), "--method=bfgs",
                   "--lambda=0.25", "--max_step_m=0.02", "--secondary=travel", "--secondary_weight=2")
    options = ccma.ControlOptions(method="bfgs", lambda_=0.25, max_step_m=0.02, travel_weight=2.0)
    result = ccma.ControlProblem(model, options).move_to(target)
    assert result.method == "bfgs" and result.secondary is not None
    assert_agrees(result, cli)


def test_control_stopped_by_an_obstacle_equals_cli():
    path = str(OBSTACLES / "pillar_detour.yaml")
    target = [1.0, 0.0, 0.6, 0, 0, 0]
    cli = run_tool("control", "--model=" + path, "--target=" + csv_numbers(target))
    result = ccma.ControlProblem(ccma.load_model(path)).move_to(target)
    assert not result.converged and "'base2' and 'pillar'" in result.warning
    assert_agrees(result, cli)


# ------------------------------------------------------------------ trajectory and plan

@pytest.mark.parametrize("model_file,path_file,obstacles", [
    ("models/4dof_reduced.yaml", "models/paths/4dof_sequential.csv", None),
    ("models/4dof_reduced.yaml", "models/paths/4dof_combined.csv", None),
    ("models/4dof_reduced.yaml", "examples/obstacles/path_x.csv", "examples/obstacles/pillar_on_base2.yaml"),
    ("examples/statics/4dof_payload.yaml", "models/paths/4dof_sequential.csv", None),
])
def test_trajectory_equals_cli(tmp_path, model_file, path_file, obstacles):
    model_path, waypoints = str(ROOT / model_file), str(ROOT / path_file)
    flags = ["--obstacles=" + str(ROOT / obstacles)] if obstacles else []
    cli = run_tool("trajectory", "--model=" + model_path, "--waypoints=" + waypoints,
                   "--out=" + str(tmp_path / "cli.csv"), *flags)
    model = ccma.load_model(model_path, obstacles=str(ROOT / obstacles) if obstacles else None)
    result = ccma.ControlProblem(model).follow(ccma.load_waypoints(waypoints), out=tmp_path / "py.csv")
    assert_agrees(result, cli)
    assert result.out == str(tmp_path / "py.csv")
    assert_table_is_csv(result.table, tmp_path / "cli.csv")
    assert result.table["reached"].dtype == bool and result.steps == len(result.table)
    assert_table_is_csv(ccma.Table.from_csv((tmp_path / "py.csv").read_text()), tmp_path / "cli.csv")
    if obstacles:
        assert "clearance_m" in result.table and result.clearance.min_on_path > 0


def test_plan_with_an_obstacles_file_equals_cli(tmp_path):
    obstacles = str(OBSTACLES / "pillar_on_base2.yaml")
    waypoints = str(OBSTACLES / "one_metre_x.csv")
    cli = run_tool("plan", "--model=" + MODEL_4DOF, "--obstacles=" + obstacles, "--waypoints=" + waypoints,
                   "--plan_iterations=20", "--out=" + str(tmp_path / "cli.csv"))
    control = ccma.ControlProblem(ccma.load_model(MODEL_4DOF, obstacles=obstacles))
    result = ccma.plan(control, ccma.load_waypoints(waypoints), plan_iterations=20)
    assert_agrees(result, cli)
    assert_table_is_csv(result.table, tmp_path / "cli.csv")
    assert result.table["reached"].dtype == bool  # the step's flag, as the CSV's 0/1
    assert result.table.stack(["x_m", "y_m", "z_m"]).shape == (result.steps, 3)


def test_plan_and_design_take_the_flags_names():
    assert "plan_iterations: int = 200" in ccma.plan.__doc__  # --plan_iterations
    assert "design_iterations" in inspect.signature(ccma.design).parameters  # --design_iterations
    with pytest.raises(TypeError):
        ccma.plan(ccma.ControlProblem(ccma.load_model(MODEL_4DOF)), [], max_iterations=3)


# ------------------------------------------------------------------ statics

@pytest.mark.parametrize("model_file,wrench", [
    ("models/4dof_reduced.yaml", [1, 2, -20, 0.1, 0, 0]),
    ("examples/statics/tripod.yaml", None),
    ("examples/statics/4dof_payload.yaml", None),
    ("examples/statics/stewart_gough_compliant.yaml", [3, -2, -40, 0.5, 0.2, 0.1]),
])
def test_statics_equals_cli(model_file, wrench):
    path = str(ROOT / model_file)
    model = ccma.load_model(path)
    u = shifted_controls(model)
    flags = ["--wrench=" + csv_numbers(wrench)] if wrench else []
    cli = run_tool("statics", "--model=" + path, "--controls=" + csv_numbers(u), *flags)
    problem = ccma.ForwardProblem(model)
    problem.assemble(u)
    assert_agrees(ccma.statics(problem, wrench=wrench), cli)


# ------------------------------------------------------------------ workspace

def test_workspace_equals_cli(tmp_path):
    cli = run_tool("workspace", "--model=" + MODEL_4DOF, "--x=-0.5:0.5", "--z=0.4:1.0", "--resolution=7",
                   "--out=" + str(tmp_path / "cli.csv"))
    result = ccma.workspace(MODEL_4DOF, {"x": (-0.5, 0.5), "z": (0.4, 1.0)}, resolution=7,
                            out=tmp_path / "py.csv")
    assert_agrees(result, cli)
    table = result.table
    assert_table_is_csv(table, tmp_path / "cli.csv")
    unreachable = ~table["reachable"]
    assert 0 < unreachable.sum() < len(table)  # both kinds of row
    assert np.isnan(table["u0"][unreachable]).all() and not np.isnan(table["u0"][~unreachable]).any()
    assert (table["sigma_min"][unreachable] == 0).all()
    assert table["wave"].dtype == np.int64 and table["limited_by"].dtype == object
    records = result.to_records()
    assert records[int(np.argmax(unreachable))]["u0"] is None
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()


# ------------------------------------------------------------------ design

def test_design_equals_cli(tmp_path):
    targets = str(ROOT / "models" / "targets" / "4dof_high_z.csv")
    vary = ["joint0:joint1", "joint3:joint4", "joint6:joint7"]
    cli = run_tool("design", "--model=" + MODEL_4DOF, "--targets=" + targets, "--out=" + str(tmp_path / "cli.yaml"),
                   "--vary_length=" + ",".join(vary))
    result = ccma.design(MODEL_4DOF, targets, vary_length=vary, out=tmp_path / "py.yaml")
    assert_agrees(result, cli)
    assert result.converged and result.reached.dtype == bool
    assert (tmp_path / "py.yaml").read_text() == (tmp_path / "cli.yaml").read_text()
    assert isinstance(result.new_model, ccma.Model)


# ------------------------------------------------------------------ replay

def test_replay_equals_cli(tmp_path):
    waypoints = str(PATHS / "4dof_sequential.csv")
    cli = run_tool("replay", "--model=" + MODEL_4DOF, "--waypoints=" + waypoints, "--out=" + str(tmp_path))
    result = ccma.replay(ccma.load_model(MODEL_4DOF), ccma.load_waypoints(waypoints))
    assert_agrees(result, cli)
    assert not set(result.to_dict()) & FILE_KEYS  # Python wrote no file
    # The command writes 12 significant digits.
    assert_table_is_csv(result.tables["end_effector"], tmp_path / "end_effector.csv", comment_lines=1, rel=1e-9)
    assert_table_is_csv(result.tables["bases"], tmp_path / "bases.csv", comment_lines=1, rel=1e-9)
    # The columns' kinds are the CSV writer's (documents/table.h), not guessed from the text.
    assert result.tables["end_effector"]["torn"].dtype == bool
    assert result.tables["bases"]["time_s"].dtype == np.float64


# ------------------------------------------------------------------ import, export, view

FIVE_BAR = ROOT / "models" / "robots" / "example-parallel-robots" / "5bar_linkage"


def test_import_equals_cli(tmp_path):
    flags = ["--from=" + str(FIVE_BAR / "robot.urdf"), "--closures=" + str(FIVE_BAR / "robot.yaml"),
             "--end_effector=effector:0.01,0,0", "--controlled=y,z"]
    cli = run_tool("import", *flags, "--out=" + str(tmp_path / "cli.yaml"))
    result = ccma.import_robot(FIVE_BAR / "robot.urdf", closures=FIVE_BAR / "robot.yaml",
                               end_effector="effector:0.01,0,0", controlled=["y", "z"],
                               out=tmp_path / "py.yaml")
    assert_agrees(result, cli)
    assert (tmp_path / "py.yaml").read_text() == (tmp_path / "cli.yaml").read_text()
    assert result.new_model.num_controls == len(result.controls)


def test_import_choosing_the_controlled_components_equals_cli(tmp_path):
    """Without --controlled, both choose what the 5-bar's two motors move at home: y, z."""
    flags = ["--from=" + str(FIVE_BAR / "robot.urdf"), "--closures=" + str(FIVE_BAR / "robot.yaml"),
             "--end_effector=effector"]
    cli = run_tool("import", *flags, "--out=" + str(tmp_path / "cli.yaml"))
    result = ccma.import_robot(FIVE_BAR / "robot.urdf", closures=FIVE_BAR / "robot.yaml",
                               end_effector="effector", out=tmp_path / "py.yaml")
    assert_agrees(result, cli)
    assert result.controlled == ["y", "z"] and result.controlled_chosen is True
    assert result.new_model.controlled == ["y", "z"]
    assert (tmp_path / "py.yaml").read_text() == (tmp_path / "cli.yaml").read_text()


def test_control_of_an_imported_idle_spin_robot_equals_cli(tmp_path):
    """cassie_like's rods spin idly between their ball joints: the controls, assembled from
    home, give the same configuration up to those spins, in Python as on the command line
    (no branch warning, the same idle_bodies)."""
    cassie = ROOT / "models" / "robots" / "example-parallel-robots" / "cassie_like"
    model_path = str(tmp_path / "cassie.yaml")
    imported = ccma.import_robot(cassie / "robot.urdf", closures=cassie / "robot.yaml", end_effector="foot",
                                 out=model_path)
    model = imported.new_model
    p = model.end_effector.p_W_home
    target = [p[0] + 0.01, p[1] + 0.01, p[2] + 0.005, 0.0, 0.0, 0.0]
    cli = run_tool("control", "--model=" + model_path, "--target=" + csv_numbers(target))
    result = ccma.ControlProblem(model).move_to(target)
    assert_agrees(result, cli)
    assert result.converged and result.warning == "" and "warning" not in cli
    assert result.from_home.reproducible and result.from_home.max_state_difference < 1e-9
    assert sorted(result.from_home.idle_bodies) == [
        "closedloop1_A", "closedloop1_B", "closedloop2_A", "closedloop2_B",
        "half_hachil_rode", "half_hachil_rode_2", "half_planta_rode", "half_planta_rode_2"]


@pytest.mark.parametrize("fmt", ["urdf", "sdf", "mjcf"])
def test_export_equals_cli(tmp_path, fmt):
    (tmp_path / "cli").mkdir()
    (tmp_path / "py").mkdir()
    name = "robot." + ("xml" if fmt == "mjcf" else fmt)
    cli = run_tool("export", "--model=" + MODEL_4DOF, "--format=" + fmt, "--out=" + str(tmp_path / "cli" / name))
    result = ccma.export(MODEL_4DOF, fmt, tmp_path / "py" / name)
    assert_agrees(result, cli, ignore={"closures"})
    assert result.out == str(tmp_path / "py" / name)
    assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / name).read_text()
    if fmt == "urdf":
        assert result.closures == str(tmp_path / "py" / "robot.closures.yaml")
        assert (tmp_path / "py" / "robot.closures.yaml").read_text() == \
            (tmp_path / "cli" / "robot.closures.yaml").read_text()
    else:
        assert result.closures is None and cli["closures"] is None
    if fmt == "mjcf":
        assert result.equalities == cli["equalities"] and result.actuators == cli["actuators"] == 9
        # MuJoCo's XML comes back through import_robot, at its keyframe `home`.
        back = ccma.import_robot(tmp_path / "py" / name, keyframe="home")
        assert back.new_model.num_controls == 9 and back.assembled


def test_view_equals_cli(tmp_path):
    if not ccma.viewer_available():
        pytest.skip("built without the viewer's JavaScript")
    trajectory = tmp_path / "path.csv"
    ccma.ControlProblem(ccma.load_model(MODEL_4DOF)).follow(
        ccma.load_waypoints(str(PATHS / "4dof_sequential.csv")), out=trajectory)
    cli = run_tool("view", "--model=" + MODEL_4DOF, "--trajectory=" + str(trajectory),
                   "--out=" + str(tmp_path / "cli.html"))
    result = ccma.view(MODEL_4DOF, trajectory=trajectory, out=tmp_path / "py.html")
    assert_agrees(result, cli)
    assert result.frames == len(ccma.Table.from_csv(trajectory.read_text()))


# ------------------------------------------------------------------ the result objects themselves

def test_item_access_warns_or_names_where_the_values_are():
    control = ccma.ControlProblem(ccma.load_model(str(OBSTACLES / "pillar_detour.yaml")))
    result = ccma.plan(control, ccma.load_waypoints(str(OBSTACLES / "path_x.csv")), plan_iterations=3)
    with pytest.warns(DeprecationWarning, match=r"result\.converged"):
        assert result["converged"] == result.converged
    with pytest.raises(KeyError, match="reached"):
        result["reached"]  # per step: the table's reached flag and its pose columns
    with pytest.raises(KeyError, match="clearance_m"):
        result["clearance"]


def test_to_dataframe_needs_pandas_and_says_so():
    result = ccma.ControlProblem(ccma.load_model(MODEL_4DOF)).follow(
        np.array([[0, 0, 0, 0.6, 0, 0, 0], [1, 0, 0.02, 0.6, 0, 0, 0]]))
    try:
        import pandas  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="to_columns"):
            result.to_dataframe()
    else:
        frame = result.to_dataframe()
        assert list(frame.columns) == result.table.names and len(frame) == result.steps
    columns = result.to_columns()
    assert list(columns) == result.table.names
    columns["time_s"][0] = 99.0  # copies: the result does not change
    assert result.table["time_s"][0] == 0.0


def test_an_out_in_no_folder_is_refused_before_anything_runs(tmp_path):
    """As the command checks --out first: ValueError naming the path, nothing moved or computed."""
    model = ccma.load_model(MODEL_4DOF)
    control = ccma.ControlProblem(model)
    missing = tmp_path / "no_such_folder" / "out.csv"
    rows = np.array([[0, 0, 0, 0.6, 0, 0, 0], [1, 0, 0.02, 0.6, 0, 0, 0]])
    with pytest.raises(ValueError, match=r"^out: .*: its folder does not exist$"):
        control.follow(rows, out=missing)
    with pytest.raises(ValueError, match="its folder does not exist"):
        ccma.plan(control, ccma.load_waypoints(str(OBSTACLES / "path_x.csv")), out=missing)
    np.testing.assert_array_equal(control.controls, model.home_controls)
    with pytest.raises(ValueError, match="its folder does not exist"):
        ccma.workspace(MODEL_4DOF, {"z": (0.5, 0.6)}, resolution=2, out=missing)
    with pytest.raises(ValueError, match="its folder does not exist"):
        ccma.export(MODEL_4DOF, "sdf", missing)
    assert not missing.parent.exists()
