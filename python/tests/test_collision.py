"""Obstacles and collisions from Python (docs/obstacles.md): obstacles added to
a loaded model, the clearance of a problem, control stopping at the margin,
and ccma.plan finding the detour the greedy walk cannot."""
import math
import pathlib

import numpy as np
import pytest

import ccma

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "obstacles"
MODELS = ROOT / "models"


def test_load_model_adds_an_obstacles_file_and_clearance_is_the_closed_form():
    model = ccma.load_model(MODELS / "4dof_reduced.yaml", obstacles=EXAMPLES / "pillar_on_base2.yaml")
    problem = ccma.ForwardProblem(model)
    c = ccma.clearance(problem)
    # base2 at (0.504903811, -0.291506351), radius 0.3; the pillar at (1, -0.29), radius 0.1.
    assert c.pair == ["base2", "pillar"] and c["pair"] == c.pair
    assert c["min"] == pytest.approx(math.hypot(1 - 0.504903811, 0.291506351 - 0.29) - 0.4, abs=1e-9)
    assert c["margin"] == pytest.approx(0.02)
    assert not c["below_margin"]
    assert ccma.clearance(ccma.ForwardProblem(ccma.load_model(MODELS / "4dof_reduced.yaml"))) is None
    with pytest.raises(ccma.ModelError):
        ccma.load_model(MODELS / "4dof_reduced.yaml", obstacles=EXAMPLES / "missing.yaml")


def test_control_stops_at_the_margin_and_names_the_pair():
    model = ccma.load_model(EXAMPLES / "pillar_detour.yaml")
    control = ccma.ControlProblem(model)
    result = control.move_to([1.0, 0.0, 0.6, 0, 0, 0])
    assert not result.converged
    assert "'base2' and 'pillar'" in result.warning
    assert result.max_clearance_violation <= 1e-9
    assert ccma.clearance(control)["min"] >= 0.05 - 1e-9


def test_plan_goes_round_the_pillar():
    model = ccma.load_model(EXAMPLES / "pillar_detour.yaml")
    control = ccma.ControlProblem(model)
    waypoints = ccma.load_waypoints(EXAMPLES / "one_metre_x.csv")
    result = ccma.plan(control, waypoints)
    assert result.used == "plan" and result.converged and result.warning == ""
    assert result.plan.reached_waypoints == 2 > result.greedy.reached_waypoints
    assert np.all(result.table["clearance_m"] >= 0.05 - 1e-9)
    assert result.clearance.min_on_path == result.table["clearance_m"].min()
    np.testing.assert_allclose(result.table.stack(["x_m", "y_m", "z_m"])[-1], [1.0, 0.0, 0.6], atol=1e-9)
    assert result.table["reached"].all()
    document = result.to_dict()
    assert document["stopped_by"] == "converged" and "shortfall" not in document
    assert document["finishing"] == {"repaired_rows": 0, "inserted_rows": 0}
    with pytest.raises(ValueError):
        ccma.plan(control, waypoints, path_weight=-1)
    with pytest.raises(ValueError):
        ccma.plan(control, waypoints, plan_time_s=-1)


def test_plan_time_bound_says_where_it_stopped():
    """plan_time_s=0 stops before the first iteration, and says so."""
    model = ccma.load_model(EXAMPLES / "pillar_detour.yaml")
    control = ccma.ControlProblem(model)
    result = ccma.plan(control, ccma.load_waypoints(EXAMPLES / "one_metre_x.csv"), plan_time_s=0)
    assert result.stopped_by == "plan_time_s" and result.iterations == 0


def test_plan_refuses_waypoints_the_csv_refuses():
    """issue 34: plan holds its waypoints to the waypoint CSV's rules (as follow
    and replay do): a NaN or decreasing time, a position or angle that is not
    finite or beyond 1e4. It returned time rows of NaN or -1e299 before."""
    model = ccma.load_model(EXAMPLES / "pillar_detour.yaml")
    control = ccma.ControlProblem(model)
    p = model.end_effector.p_W_home
    good = ccma.Waypoint(0.0, p)
    cases = [
        ([good, ccma.Waypoint(math.nan, p)], r"^waypoints\[1\]\.time \(nan\) must be a finite number in "
                                            r"\[-1e\+06, 1e\+06\] \(s\)$"),
        ([ccma.Waypoint(1.0, p), ccma.Waypoint(-1e299, p)], r"^waypoints\[1\]\.time \(-1e\+299\) must be"),
        ([ccma.Waypoint(1.0, p), ccma.Waypoint(0.5, p)],
         r"^waypoints\[1\]\.time \(0\.5\) is smaller than waypoints\[0\]\.time \(1\): time goes backwards$"),
        ([good, ccma.Waypoint(1.0, [p[0], math.inf, p[2]])], r"^waypoints\[1\]\.y \(inf\) must be a finite number in "
                                                             r"\[-10000, 10000\] \(m\)$"),
        ([ccma.Waypoint(0.0, p, [0, 2e4, 0])], r"^waypoints\[0\]\.pitch \(20000\) must be a finite number"),
    ]
    for waypoints, message in cases:
        with pytest.raises(ValueError, match=message):
            ccma.plan(control, waypoints)
    np.testing.assert_array_equal(control.controls, model.home_controls)  # nothing moved
