"""Statics from Python (docs/statics.md): the tripod's closed form, and the
same numbers as the command line."""
import math
import pathlib

import numpy as np
import pytest

import ccma
from conftest import run_tool

ROOT = pathlib.Path(__file__).resolve().parents[2]
TRIPOD = ROOT / "examples" / "statics" / "tripod.yaml"


def test_tripod_legs_carry_a_third_of_the_weight():
    problem = ccma.ForwardProblem(ccma.load_model(TRIPOD))
    r = ccma.statics(problem)
    assert r.determinate and r.balanced and r.assembled and r.warning == ""
    for a in r.actuators:
        assert abs(a.effort) == pytest.approx(3 * 9.81 * math.sqrt(2) / 3, rel=1e-9)
    foot0 = r.joints[0]
    np.testing.assert_allclose(foot0.force, [0, -9.81, 9.81], atol=1e-9)
    with pytest.raises(ValueError):
        ccma.statics(problem, wrench=[1, 2, 3])


def test_matches_the_command_line():
    model = ROOT / "models" / "4dof_reduced.yaml"
    cli = run_tool("statics", f"--model={model}", "--wrench=1,2,-20,0.1,0,0")
    r = ccma.statics(ccma.ForwardProblem(ccma.load_model(model)), wrench=[1, 2, -20, 0.1, 0, 0])
    for a, b in zip(r.actuators, cli["actuators"]):
        assert a.name == b["name"] and a.kind == b["kind"]
        assert a.effort == pytest.approx(b["effort"], abs=1e-9)
    np.testing.assert_allclose(r.ee_covariance, cli["ee_covariance"], atol=1e-15)


PAYLOAD = ROOT / "examples" / "statics" / "4dof_payload.yaml"
PAYLOAD_TARGETS = ROOT / "examples" / "statics" / "4dof_payload_targets.csv"


def test_payload_capacity_puts_the_limiting_push_on_its_limit():
    model = ccma.load_model(PAYLOAD)
    r = ccma.statics(ccma.ForwardProblem(model))
    capacity = r.payload_capacity
    cli = run_tool("statics", f"--model={PAYLOAD}")
    assert capacity.mass == pytest.approx(cli["payload_capacity"]["mass"], rel=1e-12)
    assert capacity.limiting == cli["payload_capacity"]["limiting"]
    # Pushes are linear in the payload: at the capacity the limiting base pushes exactly 60 N.
    text = PAYLOAD.read_text().replace("payload: {mass: 4}", f"payload: {{mass: {capacity.mass!r}}}")
    at_capacity = ccma.statics(ccma.ForwardProblem(ccma.load_model_from_string(text, "at_capacity.yaml")))
    pushes = {}
    for a in at_capacity.actuators:
        if a.kind in ("base_x", "base_y"):
            pushes[a.name] = pushes.get(a.name, 0.0) + a.effort ** 2
    assert math.sqrt(pushes[capacity.limiting]) == pytest.approx(60.0, rel=1e-9)
    assert max(math.sqrt(p) for p in pushes.values()) == pytest.approx(60.0, rel=1e-9)


def test_design_raises_the_payload():
    targets = np.array([[w.position[0], w.position[1], w.position[2], *w.rpy]
                        for w in ccma.load_waypoints(str(PAYLOAD_TARGETS))])
    r = ccma.design(ccma.load_model(PAYLOAD), targets,
                    vary_length=["joint2:joint1", "joint5:joint4", "joint8:joint7"],
                    max_change=0.3, objective="payload")
    assert r.converged
    o = r.objective
    assert o.name == "payload" and o.unit == "kg"
    assert o.after.value > o.before.value + 1.0
    with pytest.raises(ValueError):
        ccma.design(ccma.load_model(PAYLOAD), targets, vary_length=["joint2:joint1"], objective="stiffness")


COMPLIANT = ROOT / "examples" / "statics" / "stewart_gough_compliant.yaml"


def test_compliance_keys_of_a_compliant_model():
    text = (ROOT / "models" / "stewart_gough_6ups.yaml").read_text()
    text = text.replace("type: prismatic, actuated: true,", "type: prismatic, actuated: true, stiffness: 1.0e5,")
    model = ccma.load_model_from_string(text, "sg_compliant.yaml")
    r = ccma.statics(ccma.ForwardProblem(model), wrench=[0, 0, -100, 0, 0, 0])
    assert r.compliant_reactions and r.deflection.held
    # Six equal legs at the same slope share a vertical push: k_z = 6 k cos^2(slope).
    cos_slope = 0.870134687151
    assert r.ee_compliance[2][2] == pytest.approx(1 / (6 * 1e5 * cos_slope ** 2), rel=1e-9)
    assert r.deflection.end_effector[2] == pytest.approx(-100 * r.ee_compliance[2][2], rel=1e-9)
    np.testing.assert_allclose(np.array(r.ee_stiffness) @ np.array(r.ee_compliance), np.eye(6), atol=1e-8)
    assert r.ee_stiffness_note is None
    rigid = ccma.statics(ccma.ForwardProblem(ccma.load_model(ROOT / "models" / "stewart_gough_6ups.yaml")))
    assert rigid.deflection is None and rigid.compliant_reactions is None


def test_compliant_example_matches_the_command_line():
    cli = run_tool("statics", f"--model={COMPLIANT}")
    r = ccma.statics(ccma.ForwardProblem(ccma.load_model(COMPLIANT)))
    assert r.to_dict()["ee_compliance"] == cli["ee_compliance"]
    assert r.most_compliant.compliance == cli["most_compliant"]["compliance"]


def compliant_six_dof():
    """The bundled 6-DOF CCMA with stiff bases (model text)."""
    text = (ROOT / "models" / "6dof_asymmetric.yaml").read_text()
    at = 0
    for k in ("[2.0e4, 3.0e4, 600]", "[1.0e4, 1.0e4, 400]", "[3.0e4, 2.0e4, 900]"):
        at = text.index("type: omni,", at) + len("type: omni,")
        text = text[:at] + f" stiffness: {k}," + text[at:]
    return text


def test_loaded_assembly_matches_simulate_loaded(tmp_path):
    path = tmp_path / "6dof_compliant.yaml"
    path.write_text(compliant_six_dof())
    wrench = [3, -2, -4, 0.2, 0.1, -0.3]
    cli = run_tool("simulate", f"--model={path}", "--loaded", "--wrench=" + ",".join(map(str, wrench)))
    problem = ccma.ForwardProblem(ccma.load_model(path))
    r = problem.assemble(problem.controls, loaded=True, wrench=wrench)
    assert r.loaded.converged and r.deflection.held
    assert r.loaded.load_fraction == 1
    assert np.linalg.norm(r.deflection.end_effector[:3]) > 1e-3
    d = r.to_dict()
    for key in ("deflection", "loaded", "end_effector", "bodies", "joints"):
        assert d[key] == cli[key], key
    assert list(r.end_effector.position) == cli["end_effector"]["position"]
    # The problem stays at the rigid assembly: a plain assemble gives it back.
    rigid = problem.assemble(problem.controls)
    assert rigid.deflection is None and rigid.loaded is None
    assert np.linalg.norm(rigid.end_effector.position - r.end_effector.position) > 1e-3
    with pytest.raises(ValueError):
        problem.assemble(problem.controls, wrench=wrench)


def test_compensated_move_puts_the_loaded_end_effector_on_target(tmp_path):
    path = tmp_path / "6dof_compliant.yaml"
    path.write_text(compliant_six_dof())
    target = [0.03, -0.02, 0.62, 0, 0, 0.05]
    wrench = [3, -2, -8, 0, 0, 0]
    cli = run_tool("control", f"--model={path}", "--target=" + ",".join(map(str, target)), "--compensate",
                   "--wrench=" + ",".join(map(str, wrench)))
    control = ccma.ControlProblem(ccma.load_model(path))
    r = control.move_to(target, compensate=True, wrench=wrench)
    assert r.converged and r.compensation.converged and r.error < 1e-9
    np.testing.assert_allclose(r.end_effector.position, target[:3], atol=1e-9)
    rigid = np.array(r.compensation.rigid_end_effector.position)
    assert np.linalg.norm(rigid - target[:3]) == pytest.approx(np.linalg.norm(r.deflection.end_effector[:3]), rel=0.1)
    d = r.to_dict()
    for key in ("compensation", "deflection", "loaded", "end_effector", "controls", "error", "converged"):
        assert d[key] == cli[key], key
    plain = ccma.ControlProblem(ccma.load_model(path)).move_to(target)
    assert plain.compensation is None and plain.deflection is None


def test_compensated_path_matches_trajectory_compensate(tmp_path):
    path = tmp_path / "6dof_compliant.yaml"
    path.write_text(compliant_six_dof())
    waypoints = tmp_path / "w.csv"
    waypoints.write_text("time,x,y,z,roll,pitch,yaw\n0,0,0,0.6,0,0,0\n1,0.03,-0.02,0.62,0,0,0.05\n")
    wrench = [3, -2, -8, 0, 0, 0]
    cli_csv = tmp_path / "cli.csv"
    cli = run_tool("trajectory", f"--model={path}", f"--waypoints={waypoints}", f"--out={cli_csv}", "--compensate",
                   "--wrench=" + ",".join(map(str, wrench)))
    control = ccma.ControlProblem(ccma.load_model(path))
    r = control.follow(ccma.load_waypoints(waypoints), out=tmp_path / "py.csv", compensate=True, wrench=wrench)
    assert r.converged and r.compensation["max_miss"] < 1e-9 and r.compensation["rounds"] >= r.steps
    d = r.to_dict()
    for key in ("compensation", "end_effector", "controls", "steps", "converged", "max_error"):
        assert d[key] == cli[key], key
    def rows(path):  # the CSV without its timing column
        lines = [line.split(",") for line in path.read_text().splitlines()]
        keep = [i for i, name in enumerate(lines[0]) if name != "solve_time_ms"]
        return [[line[i] for i in keep] for line in lines]
    assert rows(tmp_path / "py.csv") == rows(cli_csv)
    # The last row is the loaded configuration: its end-effector is on the last waypoint.
    np.testing.assert_allclose(r.end_effector.position, [0.03, -0.02, 0.62], atol=1e-9)
    with pytest.raises(ValueError):
        control.follow(ccma.load_waypoints(waypoints), wrench=wrench)
