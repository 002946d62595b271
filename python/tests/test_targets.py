"""Targets of ControlProblem.move_to, step and objective: six numbers, or only
the model's controlled components (as `ccma control --target` takes them),
with the same results as the tool; any other length is a ValueError."""
import numpy as np
import pytest

import ccma
from conftest import MODELS, csv_numbers, run_tool
from test_agreement import TOL, control_target

COMPONENTS = ["x", "y", "z", "roll", "pitch", "yaw"]
PARTLY_CONTROLLED = [m for m in MODELS if len(ccma.load_model(str(m)).controlled) < 6]


def short_form(model, full):
    return [full[COMPONENTS.index(c)] for c in model.controlled]


def test_some_models_control_fewer_than_six_components():
    names = sorted(m.stem for m in PARTLY_CONTROLLED)
    assert "4dof_reduced" in names and "planar_3rpr" in names  # x y z yaw; x y yaw


@pytest.mark.parametrize("path", PARTLY_CONTROLLED, ids=[m.stem for m in PARTLY_CONTROLLED])
def test_controlled_components_only_match_the_tool(path):
    model = ccma.load_model(str(path))
    target = short_form(model, control_target(model))
    assert len(target) == len(model.controlled) < 6
    cli = run_tool("control", "--model=%s" % path, "--target=" + csv_numbers(target))
    r = ccma.ControlProblem(model).move_to(target)
    assert r.converged and cli["converged"]
    assert r.steps == cli["steps"] and r.iterations == cli["iterations"]
    np.testing.assert_allclose(r.controls, cli["controls"], rtol=0, atol=TOL)
    np.testing.assert_allclose(r.target, cli["target"], rtol=0, atol=TOL)  # filled in the same way
    np.testing.assert_allclose(r.end_effector.position, cli["end_effector"]["position"], rtol=0, atol=TOL)


def test_short_form_means_the_full_target():
    """On 4dof_reduced [x, y, z, yaw] is [x, y, z, 0, 0, yaw] from home (roll and
    pitch are not controlled, so they are filled in from the current pose, 0)."""
    model = ccma.load_model(str(next(m for m in MODELS if m.stem == "4dof_reduced")))
    assert model.controlled == ["x", "y", "z", "yaw"]
    x, y, z, yaw = 0.02, 0.05, 0.62, 0.1
    short = ccma.ControlProblem(model).move_to([x, y, z, yaw])
    full = ccma.ControlProblem(model).move_to([x, y, z, 0.0, 0.0, yaw])
    np.testing.assert_array_equal(short.target, [x, y, z, 0.0, 0.0, yaw])
    np.testing.assert_array_equal(short.controls, full.controls)
    assert short.converged and short.steps == full.steps == 20
    # The pose reached, in closed form: the target itself.
    np.testing.assert_allclose(short.end_effector.position, [x, y, z], rtol=0, atol=1e-9)
    assert abs(short.end_effector.rpy[2] - yaw) < 1e-9

    a, b = ccma.ControlProblem(model), ccma.ControlProblem(model)
    o_short, g_short = a.objective([0.03, 0.05, 0.62, 0.1])
    o_full, g_full = b.objective([0.03, 0.05, 0.62, 0, 0, 0.1])
    assert o_short == o_full and o_short == pytest.approx(0.5 * (0.03**2 + 0.05**2 + 0.02**2 + 0.1**2), rel=1e-12)
    np.testing.assert_array_equal(g_short, g_full)
    step_short, step_full = a.step([0.001, 0, 0.6, 0]), b.step([0.001, 0, 0.6, 0, 0, 0])
    assert step_short.reached and step_full.reached
    np.testing.assert_array_equal(a.controls, b.controls)


@pytest.mark.parametrize("values", [[], [0.6], [0, 0, 0.6], [0, 0, 0.6, 0, 0], [0, 0, 0.6, 0, 0, 0, 0]])
def test_wrong_lengths_raise_value_error_like_the_tool(values):
    path = str(next(m for m in MODELS if m.stem == "4dof_reduced"))
    control = ccma.ControlProblem(ccma.load_model(path))
    expected = ("target: expected 6 values x,y,z,roll,pitch,yaw or 4 (the controlled x,y,z,yaw); got %d"
                % len(values))
    for call in (control.move_to, control.step, lambda t: control.objective(t)):
        with pytest.raises(ValueError) as e:
            call(values)
        assert not isinstance(e.value, TypeError)
        assert str(e.value) == expected
    if values:  # the tool says the same about --target (an empty flag is another error)
        cli = run_tool("control", "--model=" + path, "--target=" + csv_numbers(values), expect=2)
        assert "--" + expected in cli.stderr and cli.stdout == ""


def test_a_six_component_model_takes_six():
    model = ccma.load_model(str(next(m for m in MODELS if m.stem == "6dof_symmetric")))
    assert len(model.controlled) == 6
    with pytest.raises(ValueError, match=r"or 6 \(the controlled x,y,z,roll,pitch,yaw\); got 4$"):
        ccma.ControlProblem(model).move_to([0, 0, 0.6, 0])
