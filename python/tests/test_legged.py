"""Legged bases from Python: six controls each, where they sit in u, a body raised
and a target reached, and the wrench statics reports (docs/model_format.md, "Legged agents")."""
import os

import numpy as np
import pytest

import ccma

MODELS = os.path.join(os.path.dirname(__file__), "..", "..", "models")
LEGGED = os.path.join(MODELS, "6dof_three_legged.yaml")


def test_a_legged_base_has_six_named_controls():
    model = ccma.load_model(LEGGED)
    assert model.num_controls == 18
    assert [model.base_control(k) for k in range(model.num_bases)] == [0, 6, 12]
    base = model.mobile_bases[1]
    assert base.type == "legged"
    assert base.control_names == ["x_m", "y_m", "theta_rad", "height_m", "roll_rad", "pitch_rad"]
    assert base.body_height == pytest.approx(0.45)
    omni = ccma.load_model(os.path.join(MODELS, "4dof_reduced.yaml"))
    assert omni.mobile_bases[0].control_names == ["x_m", "y_m", "theta_rad"]
    assert omni.base_control(1) == 3


def test_raising_every_body_raises_the_platform_by_as_much():
    model = ccma.load_model(LEGGED)
    forward = ccma.ForwardProblem(model)
    home = forward.end_effector.position.copy()
    u = model.home_controls
    for k in range(model.num_bases):
        u[model.base_control(k) + 3] += 0.07
    assert forward.assemble(u).converged
    np.testing.assert_allclose(forward.end_effector.position - home, [0, 0, 0.07], atol=1e-12)


def test_move_to_and_statics_on_legged_bases():
    model = ccma.load_model(LEGGED)
    control = ccma.ControlProblem(model)
    result = control.move_to([0.05, 0.03, 1.0, 0.05, -0.04, 0.1])
    assert result.converged
    np.testing.assert_allclose(control.forward.end_effector.position, [0.05, 0.03, 1.0], atol=1e-9)
    kinds = [a["kind"] for a in ccma.statics(control.forward).to_dict()["actuators"][:6]]
    assert kinds == ["base_force_x", "base_force_y", "base_force_z",
                     "base_moment_x", "base_moment_y", "base_moment_z"]


def test_replay_reports_the_gait_as_the_tool_does():
    model = ccma.load_model(LEGGED)
    walk = np.array([[0, 0, 0, 0.95, 0, 0, 0], [2, 0.1, 0, 0.95, 0, 0, 0]], dtype=float)
    result = ccma.replay(model, walk, ccma.ReplayOptions(noise="none", gait_bob_m=0.02))
    gait = result.to_dict()["gait"]
    assert gait["bob_m"] == 0.02 and gait["hz"] == 2.0
    assert 3.0 < gait["rmse_from_gait"]["z_mm"] < 20.0
    still = ccma.replay(model, walk, ccma.ReplayOptions(noise="none", gait_bob_m=0.0, gait_sway_rad=0.0))
    assert still.to_dict()["gait"]["rmse_from_gait"]["z_mm"] < 1e-9
    assert list(result.tables["bases"].names)[1:7] == [
        "set0_x_m", "set0_y_m", "set0_theta_rad", "set0_height_m", "set0_roll_rad", "set0_pitch_rad"]
