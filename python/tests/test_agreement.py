"""The Python API gives the C++ results (through `ccma`, the CLI) to 1e-12 on
every bundled model: counts, forward assembly and control."""
import numpy as np
import pytest

import ccma
from conftest import ROOT, csv_numbers, run_tool

MODELS_DIR = ROOT / "models"

TOL = 1e-12


def test_counts_match_check(model_path):
    model = ccma.load_model(model_path)
    check = run_tool("check", "--model=" + model_path)
    assert model.name == check["model"]
    assert model.num_bodies == check["bodies"]
    assert model.num_bases == check["mobile_bases"]
    assert len(model.joints) == check["joints"]
    assert model.state_size == check["state_size"]
    assert model.num_controls == check["controls"]
    assert model.num_constraints == check["constraints"]
    assert ccma.analyze_mobility(model).constraints == check["constraints"]
    mobility = ccma.analyze_mobility(model)
    assert mobility.end_effector_dof == check["end_effector_dof"]
    assert mobility.rigid_with_controls_fixed == check["rigid_with_controls_fixed"]


def shifted_controls(model):
    """Every base 15 mm along x and 10 mm along y (a rigid translation of the
    whole mechanism: reachable by every model), actuated joints 0.01 in."""
    u = model.home_controls.copy()
    for k in range(model.num_bases):
        u[3 * k] += 0.015
        u[3 * k + 1] -= 0.010
    u[3 * model.num_bases:] += 0.01
    return u


def test_assemble_matches_simulate(model_path):
    model = ccma.load_model(model_path)
    u = shifted_controls(model)
    cli = run_tool("simulate", "--model=" + model_path, "--controls=" + csv_numbers(u))
    r = ccma.ForwardProblem(model).assemble(u)
    assert r.assembled == cli["assembled"]
    assert r.iterations == cli["iterations"]
    assert abs(r.residual_energy - cli["residual_energy"]) <= TOL
    np.testing.assert_allclose(r.end_effector.position, cli["end_effector"]["position"], rtol=0, atol=TOL)
    np.testing.assert_allclose(r.end_effector.rotation, cli["end_effector"]["rotation"], rtol=0, atol=TOL)
    np.testing.assert_allclose(r.controls, cli["controls"], rtol=0, atol=TOL)


def test_body_poses_and_joints_match_simulate(model_path):
    model = ccma.load_model(model_path)
    u = shifted_controls(model)
    cli = run_tool("simulate", "--model=" + model_path, "--controls=" + csv_numbers(u))
    forward = ccma.ForwardProblem(model)
    forward.assemble(u)
    poses = forward.body_poses()
    assert [p.name for p in poses] == [b["name"] for b in cli["bodies"]]
    for p, b in zip(poses, cli["bodies"]):
        np.testing.assert_allclose(p.position, b["position"], rtol=0, atol=TOL)
        np.testing.assert_allclose(p.quaternion, b["quaternion"], rtol=0, atol=TOL)
    coords = forward.joint_coordinates()
    assert len(coords) == len(cli["joints"])
    for c, j in zip(coords, cli["joints"]):
        assert model.joints[c.joint].name == j["name"]
        assert abs(c.q - j["q"]) <= TOL
    assert forward.limits_violated() == cli["limits_violated"]


def control_target(model):
    """2 cm up and 1 cm along y from home (within every bundled workspace)."""
    p = model.end_effector.p_W_home
    return [p[0], p[1] + 0.01, p[2] + 0.02, 0.0, 0.0, 0.0]


def test_move_to_matches_control(model_path):
    model = ccma.load_model(model_path)
    target = control_target(model)
    cli = run_tool("control", "--model=" + model_path, "--target=" + csv_numbers(target))
    r = ccma.ControlProblem(model).move_to(target)
    assert r.converged == cli["converged"]
    assert r.steps == cli["steps"]
    assert r.iterations == cli["iterations"]
    np.testing.assert_allclose(r.controls, cli["controls"], rtol=0, atol=TOL)
    np.testing.assert_allclose(r.end_effector.position, cli["end_effector"]["position"], rtol=0, atol=TOL)
    assert abs(r.residual_energy - cli["residual_energy"]) <= TOL


def test_free_motions_match_check(tmp_path):
    """A joint taken out of 4dof_reduced leaves leg 2 hanging: Python names the
    same moving bodies as `ccma check` ([post2, link2] and [link2]), along
    unit, orthogonal directions in the null space."""
    text = (MODELS_DIR / "4dof_reduced.yaml").read_text()
    line = next(l for l in text.splitlines(keepends=True) if l.startswith("  - {type: revolute, between: [link2, ee]"))
    path = tmp_path / "without_joint.yaml"
    path.write_text(text.replace(line, ""))
    model = ccma.load_model(str(path))
    mobility = ccma.analyze_mobility(model)
    names = [motion.bodies for motion in mobility.free_motions]
    assert names == [["post2", "link2"], ["link2"]]
    assert mobility.free_motions_listed
    check = run_tool("check", "--model=" + str(path))
    assert names == [motion["bodies"] for motion in check["free_motions"]]
    d = np.array([motion.direction for motion in mobility.free_motions])
    assert np.allclose(d @ d.T, np.eye(2), atol=1e-12)
    assert ccma.analyze_mobility(ccma.load_model(str(MODELS_DIR / "4dof_reduced.yaml"))).free_motions == []
