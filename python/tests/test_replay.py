"""ccma.replay gives the numbers `ccma replay` writes (same seed)."""
import csv

import numpy as np

import ccma
from conftest import ROOT, run_tool


def test_replay_matches_cli(tmp_path):
    model_path = str(ROOT / "models" / "4dof_reduced.yaml")
    waypoints = str(ROOT / "models" / "paths" / "4dof_sequential.csv")
    cli = run_tool("replay", "--model=" + model_path, "--waypoints=" + waypoints, "--out=" + str(tmp_path))
    r = ccma.replay(ccma.load_model(model_path), ccma.load_waypoints(waypoints))
    assert r.trustworthy == cli["trustworthy"]
    assert len(r.table) == r.samples == cli["samples"]
    assert abs(r.rmse.x_mm - cli["rmse"]["x_mm"]) < 1e-12
    assert abs(r.rmse.z_mm - cli["rmse"]["z_mm"]) < 1e-12
    assert abs(r.rmse.yaw_rad - cli["rmse"]["yaw_rad"]) < 1e-12
    with open(tmp_path / "end_effector.csv") as f:
        rows = [row for row in csv.reader(line for line in f if not line.startswith("#"))]
    header, data = rows[0], np.array(rows[1:], dtype=float)
    ee = r.tables["end_effector"]
    np.testing.assert_allclose(ee["x_m"], data[:, header.index("x_m")], rtol=0, atol=1e-11)
    np.testing.assert_allclose(ee["cmd_z_m"], data[:, header.index("cmd_z_m")], rtol=0, atol=1e-11)
    bases = r.tables["bases"]
    assert len(bases.names) == 2 + 6 * 3 and len(bases) == r.samples  # time, set and true pose per base, torn
    assert ee["torn"].dtype == bool and not ee["torn"].any()
    assert r.torn_samples == cli["torn_samples"] == 0


def test_replay_takes_paths_as_the_command_does():
    """ccma.replay(model_path, "walk.csv"): the paths the command takes, the same numbers."""
    import pathlib
    model_path = ROOT / "models" / "4dof_reduced.yaml"
    waypoints = ROOT / "models" / "paths" / "4dof_sequential.csv"
    by_path = ccma.replay(str(model_path), pathlib.Path(waypoints))
    by_object = ccma.replay(ccma.load_model(str(model_path)), ccma.load_waypoints(str(waypoints)))
    assert by_path.samples == by_object.samples
    np.testing.assert_array_equal(by_path.table["x_m"], by_object.table["x_m"])
    import pytest
    with pytest.raises(ccma.WaypointError):
        ccma.replay(str(model_path), str(ROOT / "models" / "no_such_walk.csv"))


def test_replay_takes_an_array_and_options():
    model = ccma.load_model(str(ROOT / "models" / "4dof_reduced.yaml"))
    waypoints = np.array([[0, 0, 0, 0.6, 0, 0, 0], [2, 0, 0.02, 0.6, 0, 0, 0]])
    options = ccma.ReplayOptions(noise="none", output_hz=10, seed=7)
    assert (options.noise, options.seed, options.output_hz) == ("none", 7, 10)
    r = ccma.replay(model, waypoints, options)
    assert r.trustworthy and r.samples == len(r.table) == 31  # 0 .. 3 s (1 s settling) at 10 Hz
    ee = r.table
    tracked = ee.stack(["x_m", "y_m", "z_m"])
    commanded = ee.stack(["cmd_x_m", "cmd_y_m", "cmd_z_m"])
    assert np.abs(tracked - commanded).max() < 1e-3
    assert np.abs(ee["err_y_mm"] - 1000 * (ee["y_m"] - ee["cmd_y_m"])).max() < 1e-9


def test_replay_rejects_bad_input():
    model = ccma.load_model(str(ROOT / "models" / "4dof_reduced.yaml"))
    import pytest
    with pytest.raises(ValueError):
        ccma.replay(model, [])
    with pytest.raises(ValueError):
        ccma.ReplayOptions(noise="loud")


def test_replay_and_follow_refuse_positions_the_csv_refuses():
    """issue 34: a waypoint's position or angle must be finite and within 1e4,
    as in the waypoint CSV; the message names the waypoint and the column."""
    import math
    import pytest
    model = ccma.load_model(str(ROOT / "models" / "4dof_reduced.yaml"))
    p = model.end_effector.p_W_home
    rows = np.array([[0, p[0], p[1], p[2], 0, 0, 0], [1, p[0], p[1], math.nan, 0, 0, 0]])
    with pytest.raises(ValueError, match=r"^waypoints\[1\]\.z \(nan\) must be a finite number in \[-10000, 10000\] "
                                         r"\(m\)$"):
        ccma.replay(model, rows)
    rows[1, 3], rows[1, 6] = p[2], -1e5
    with pytest.raises(ValueError, match=r"^waypoints\[1\]\.yaw \(-100000\) must be a finite number in "
                                         r"\[-10000, 10000\] \(rad\)$"):
        ccma.ControlProblem(model).follow(rows)
    with pytest.raises(ValueError, match=r"^waypoints: 1000001 rows; at most 1000000 are allowed$"):
        ccma.ControlProblem(model).follow(np.zeros((1000001, 7)))
