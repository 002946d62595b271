"""Inverse dynamics and retiming from Python (docs/dynamics.md): the arm's closed
form, the command line's numbers and files, retime's output within every limit,
and bad input as ValueError."""
import math
import pathlib

import numpy as np
import pytest

import ccma
from conftest import run_tool

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAYLOAD = ROOT / "examples" / "dynamics" / "4dof_payload.yaml"

ARM = ("name: arm\nbodies:\n  - {name: arm, position: [0.2, 0, 0], mass: 2.5, com: [0.4, 0, 0],"
       " inertia: [0.02, 0.03, 0.025, 0.004, -0.003, 0.002]}\n"
       "joints:\n  - {name: hinge, type: revolute, actuated: true, between: [world, arm], point: [0, 0, 0], "
       "axis: [0, -1, 0], effort_limits: [-30, 30], velocity_limit: 1.5}\n"
       "end_effector: {body: arm, point: [0.5, 0, 0], controlled: [x, z]}\n")


def arm_path(tmp_path, theta0=-0.4, rate=1.3, rows=11, dt=0.1):
    """theta(t) = theta0 + rate t, which a natural spline reproduces exactly."""
    lines = ["time_s,u_hinge_rad,x_m,y_m,z_m"]
    for r in range(rows):
        t = r * dt
        q = theta0 + rate * t
        lines.append("%.17g,%.17g,%.17g,0,%.17g" % (t, q, 0.5 * math.cos(q), 0.5 * math.sin(q)))
    path = tmp_path / "arm_path.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_the_arm_turning_at_a_constant_rate_needs_the_gravity_torque(tmp_path):
    problem = ccma.ForwardProblem(ccma.load_model_from_string(ARM, "arm.yaml"))
    r = ccma.dynamics(problem, arm_path(tmp_path))
    assert isinstance(r, ccma.DynamicsResult)
    assert r.rows == 11 and r.assembled and r.within_limits and r.warning == ""
    m, l, inertia = 2.5, 0.4, 0.03 + 2.5 * 0.4 ** 2
    q = -0.4 + 1.3 * 0.1 * np.arange(11)
    np.testing.assert_allclose(r.table["u_hinge_Nm"], m * 9.81 * l * np.cos(q), rtol=0, atol=1e-9)
    np.testing.assert_allclose(r.table["kinetic_J"], 0.5 * inertia * 1.3 ** 2, rtol=0, atol=1e-12)
    np.testing.assert_allclose(r.table["power_W"], r.table["u_hinge_Nm"] * 1.3, rtol=0, atol=1e-9)
    assert r.actuators[0].name == "hinge" and list(r.actuators[0].limit) == [-30, 30]


def test_dynamics_and_retime_match_the_command_line(tmp_path):
    model = ccma.load_model(PAYLOAD)
    control = ccma.ControlProblem(model)
    p = control.current_pose[:3]
    waypoints = [ccma.Waypoint(0, p), ccma.Waypoint(20, p + [0.05, 0.03, 0]), ccma.Waypoint(40, p + [0, 0.06, 0])]
    followed = control.follow(waypoints, out=tmp_path / "path.csv")
    assert followed.converged

    r = ccma.dynamics(ccma.ForwardProblem(model), followed, out=tmp_path / "py_dynamics.csv")
    cli = run_tool("dynamics", f"--model={PAYLOAD}", f"--trajectory={tmp_path / 'path.csv'}",
                   f"--out={tmp_path / 'cli_dynamics.csv'}")
    mine = r.to_dict()
    assert mine.pop("out") == str(tmp_path / "py_dynamics.csv")
    cli.pop("out")
    assert mine == cli  # the same document, number for number
    assert (tmp_path / "py_dynamics.csv").read_bytes() == (tmp_path / "cli_dynamics.csv").read_bytes()
    # A path string gives the same result as the follow() result's table.
    assert ccma.dynamics(control, str(tmp_path / "path.csv")).to_dict() == cli

    t = ccma.retime(control, tmp_path / "path.csv", out=tmp_path / "py_retimed.csv")
    cli_t = run_tool("retime", f"--model={PAYLOAD}", f"--trajectory={tmp_path / 'path.csv'}",
                     f"--out={tmp_path / 'cli_retimed.csv'}")
    assert isinstance(t, ccma.RetimeResult) and t.feasible
    assert t.duration_s < t.original_duration_s
    mine = t.to_dict()
    mine.pop("out")
    cli_t.pop("out")
    assert mine == cli_t
    assert t.csv_text == (tmp_path / "cli_retimed.csv").read_text()
    assert (tmp_path / "py_retimed.csv").read_text() == t.csv_text
    assert t.table["time_s"][-1] == pytest.approx(t.duration_s, rel=1e-12)
    # The retimed path, run through dynamics, is within every limit.
    assert ccma.dynamics(control, t).within_limits


def test_retime_of_a_path_beyond_its_limit_at_rest_says_so(tmp_path):
    heavy = ARM.replace("mass: 2.5", "mass: 25")
    problem = ccma.ForwardProblem(ccma.load_model_from_string(heavy, "heavy.yaml"))
    t = ccma.retime(problem, arm_path(tmp_path), out=tmp_path / "never.csv")
    assert not t.feasible and t.csv_text is None and t.duration_s is None
    assert t.infeasible.control == "hinge" and t.infeasible.row == 0
    assert "hinge" in t.warning
    assert not (tmp_path / "never.csv").exists()
    with pytest.raises(KeyError):
        t.table


def test_bad_input_is_a_value_error_naming_line_and_column(tmp_path):
    problem = ccma.ForwardProblem(ccma.load_model_from_string(ARM, "arm.yaml"))
    bad = tmp_path / "bad.csv"
    bad.write_text("time_s,u_hinge_rad\n0,0.1\n1,nan\n")
    with pytest.raises(ValueError, match=r"bad.csv:3"):
        ccma.dynamics(problem, bad)
    backwards = tmp_path / "backwards.csv"
    backwards.write_text("time_s,u_hinge_rad\n1,0.1\n0,0.2\n")
    with pytest.raises(ValueError, match=r"backwards.csv:3"):
        ccma.retime(problem, backwards)
    with pytest.raises(ValueError, match="trajectory CSV"):
        ccma.dynamics(problem, tmp_path / "missing.csv")
    with pytest.raises(TypeError, match="trajectory must be"):
        ccma.dynamics(problem, 42)
    unlimited = ARM.replace(", effort_limits: [-30, 30], velocity_limit: 1.5", "")
    with pytest.raises(ValueError, match="retime"):
        ccma.retime(ccma.ForwardProblem(ccma.load_model_from_string(unlimited, "free.yaml")), arm_path(tmp_path))


def test_view_colours_the_efforts_of_a_trajectory(tmp_path):
    if not ccma.viewer_available():
        pytest.skip("this build carries no viewer JavaScript")
    heavy = ARM.replace("effort_limits: [-30, 30]", "effort_limits: [-20, 9]")
    model = ccma.load_model_from_string(heavy, "heavy.yaml")
    path = tmp_path / "arm_view.csv"
    rows = ["time_s,target_x_m,target_y_m,target_z_m,x_m,y_m,z_m,u_hinge_rad"]
    for r in range(11):
        q = -0.4 + 0.13 * r
        x, z = 0.5 * math.cos(q), 0.5 * math.sin(q)
        rows.append("%.17g,%.17g,0,%.17g,%.17g,0,%.17g,%.17g" % (0.1 * r, x, z, x, z, q))
    path.write_text("\n".join(rows) + "\n")
    efforts = tmp_path / "arm_efforts.csv"
    r = ccma.dynamics(ccma.ForwardProblem(model), path, out=efforts)
    page, info = ccma.view_html(model, trajectory=str(path), dynamics=str(efforts))
    # The share of the 9 N m limit: the largest gravity torque over 9.
    peak = max(abs(a.peak_effort) for a in r.actuators)
    assert info.max_effort_share == pytest.approx(peak / 9, rel=1e-9)
    assert info.effort_frames_beyond_limit == sum(1 for e in r.table["u_hinge_Nm"] if e > 9)
    assert '"efforts"' in page
    with pytest.raises(ValueError, match="dynamics goes with trajectory"):
        ccma.view_html(model, dynamics=str(efforts))
