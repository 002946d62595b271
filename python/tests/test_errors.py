"""Errors reach Python as exceptions with the C++ messages (file:line: key)."""
import math

import numpy as np
import pytest

import ccma
from conftest import ROOT

MODEL = str(ROOT / "models" / "4dof_reduced.yaml")


def test_model_error_names_file_line_and_key(tmp_path):
    bad = tmp_path / "bad.yaml"
    text = (ROOT / "models" / "4dof_reduced.yaml").read_text().replace("axis: [0, 0, 1]", "axis: [0, 0, 0]", 1)
    bad.write_text(text)
    line = next(i + 1 for i, l in enumerate(text.splitlines()) if "axis: [0, 0, 0]" in l)
    with pytest.raises(ccma.ModelError) as e:
        ccma.load_model(str(bad))
    assert str(e.value).startswith("%s:%d:" % (bad, line))
    assert "axis" in str(e.value)
    assert isinstance(e.value, ValueError)


def test_missing_file_and_string_source():
    with pytest.raises(ccma.ModelError, match="no_such_file.yaml"):
        ccma.load_model("no_such_file.yaml")
    with pytest.raises(ccma.ModelError, match="^mine:"):
        ccma.load_model_from_string("name: [", "mine")


def test_unknown_key_warns(tmp_path):
    path = tmp_path / "extra.yaml"
    path.write_text((ROOT / "models" / "4dof_reduced.yaml").read_text() + "\ncolour: blue\n")
    with pytest.warns(UserWarning, match="colour"):
        ccma.load_model(str(path))


def test_bad_controls_raise_value_error():
    model = ccma.load_model(MODEL)
    forward = ccma.ForwardProblem(model)
    with pytest.raises(ValueError):
        forward.solve(np.zeros(model.num_controls + 1))
    u = model.home_controls.copy()
    u[0] = math.nan
    with pytest.raises(ValueError):
        forward.assemble(u)
    u[0] = 1e300
    with pytest.raises(ValueError):
        forward.assemble(u)
    with pytest.raises(ValueError):
        ccma.ControlProblem(model).move_to([0, 0, math.inf, 0, 0, 0])
    with pytest.raises(ValueError):
        forward.set_state(np.zeros((model.num_bodies, 7)))  # zero quaternions


def test_python_refuses_what_the_cli_refuses():
    """NaN or huge controls, states and design values are refused as the CLI refuses
    them, instead of answering NaN, "not rigid" or a negative singular value."""
    model = ccma.load_model(MODEL)
    u = model.home_controls.copy()
    u[1] = math.nan
    with pytest.raises(ValueError, match=r"controls: entry 1 \(nan\) must be a finite number"):
        ccma.analyze_mobility(model, controls=u)
    with pytest.raises(ValueError, match="controls: expected"):
        ccma.analyze_mobility(model, controls=model.home_controls[:-1])
    forward = ccma.ForwardProblem(model)
    huge = forward.state.copy()
    huge[0, :4] = 1e308  # would overflow the norm and store a zero quaternion
    with pytest.raises(ValueError, match="state: every entry must be a finite number"):
        forward.set_state(huge)
    assert np.isclose(np.linalg.norm(forward.state[0, :4]), 1.0)  # unchanged
    # Design parameters are lengths [m]: 1e300 is refused.
    targets = np.array([[0.0, 0.0, 0.6, 0.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match="values: one finite number within"):
        ccma.evaluate_design(model, targets, [1e300], vary=["joint1.z"])


def test_follow_refuses_times_the_waypoint_csv_refuses():
    """follow() holds its times to the CSV's rules (docs/waypoints.md): finite, within 1e6 s,
    never smaller than the one before; the error names the waypoint. Equal times are allowed."""
    model = ccma.load_model(MODEL)
    p = model.end_effector.p_W_home

    def rows(times):
        return np.array([[t, p[0], p[1] + 0.01 * i, p[2], 0, 0, 0] for i, t in enumerate(times)])

    control = ccma.ControlProblem(model)
    with pytest.raises(ValueError, match=r"^waypoints\[2\]\.time \(0\.5\) is smaller than waypoints\[1\]\.time "
                                         r"\(1\): time goes backwards$"):
        control.follow(rows([0, 1, 0.5]))
    with pytest.raises(ValueError, match=r"^waypoints\[1\]\.time \(nan\) must be a finite number in "
                                         r"\[-1e\+06, 1e\+06\] \(s\)$"):
        control.follow(rows([0, math.nan, 2]))
    with pytest.raises(ValueError, match=r"^waypoints\[0\]\.time \(inf\)"):
        control.follow([ccma.Waypoint(math.inf, p)])
    with pytest.raises(ValueError, match=r"^waypoints\[1\]\.time \(2e\+06\)"):
        control.follow(rows([0, 2e6]))
    # Nothing moved: the refused paths were checked before the first step.
    np.testing.assert_array_equal(control.controls, model.home_controls)
    # Equal times are allowed, as in the CSV: two legs, the second one in no time.
    result = control.follow(rows([0, 1, 1]))
    assert result.converged
    assert result.table["time_s"][0] == 0 and result.table["time_s"][-1] == 1
    assert np.abs(result.table.stack(["x_m", "y_m", "z_m"])[-1] - [p[0], p[1] + 0.02, p[2]]).max() < 1e-9


def test_objective_refuses_a_nan_target():
    control = ccma.ControlProblem(ccma.load_model(MODEL))
    with pytest.raises(ValueError, match=r"target: y \(nan\) must be a finite number in \[-10000, 10000\]"):
        control.objective([0, math.nan, 0.6, 0, 0, 0])


def test_bad_options_raise_value_error():
    model = ccma.load_model(MODEL)
    with pytest.raises(ValueError, match="lambda"):
        ccma.ControlProblem(model, ccma.ControlOptions(lambda_=2.0))
    with pytest.raises(ValueError):
        ccma.ControlOptions(method="newton")
    with pytest.raises(TypeError, match="no_such_option"):
        ccma.ControlOptions(no_such_option=1)
    with pytest.raises(TypeError, match="assembly_tolerances"):
        ccma.ForwardOptions(assembly_tolerances=1e-12)
    ok, why = ccma.ForwardOptions(assembly_tolerance=-1.0).is_valid()
    assert not ok and "assembly_tolerance" in why


def test_waypoint_error(tmp_path):
    path = tmp_path / "w.csv"
    path.write_text("time,x,y,z,roll,pitch,yaw\n0,0,0,zero,0,0,0\n")
    with pytest.raises(ccma.WaypointError, match="w.csv:2"):
        ccma.load_waypoints(str(path))


def test_warnings_as_errors_raise_the_warning(tmp_path):
    path = tmp_path / "extra.yaml"
    path.write_text((ROOT / "models" / "4dof_reduced.yaml").read_text() + "\ncolour: blue\n")
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(UserWarning, match="colour"):
            ccma.load_model(path)  # a pathlib.Path works too
        with pytest.raises(UserWarning, match="colour"):
            ccma.load_model_from_string(path.read_text(), "text")


def test_controls_are_copies():
    model = ccma.load_model(MODEL)
    forward = ccma.ForwardProblem(model)
    before = forward.controls
    forward.assemble(before + 0.001)
    np.testing.assert_array_equal(before, model.home_controls)


def test_model_outlives_its_problem():
    """The problem keeps the model alive (the C++ problem holds a reference)."""
    forward = ccma.ForwardProblem(ccma.load_model(MODEL))
    import gc
    gc.collect()
    model = ccma.load_model(MODEL)
    assert forward.assemble(model.home_controls).assembled


def test_every_exception_class_says_when_it_is_raised():
    """ccma's own exception classes (all of them) have docstrings naming what raises
    them and what they carry."""
    from ccma import _ccma
    classes = {n: c for n, c in vars(_ccma).items() if isinstance(c, type) and issubclass(c, BaseException)}
    assert sorted(classes) == ["ModelError", "ViewInputError", "WaypointError", "WorkBoundError"]
    raisers = {"ModelError": "load_model", "ViewInputError": "view_html", "WaypointError": "load_waypoints",
               "WorkBoundError": "workspace"}
    for name, cls in classes.items():
        assert cls.__doc__ and cls.__doc__.strip(), name
        assert cls.__doc__ != ValueError.__doc__, name
        assert raisers[name] in cls.__doc__ and "message" in cls.__doc__, name
        assert getattr(ccma, name) is cls and issubclass(cls, ValueError)
