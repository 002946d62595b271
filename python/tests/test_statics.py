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
    assert r["determinate"] and r["balanced"]
    for a in r["actuators"]:
        assert abs(a["effort"]) == pytest.approx(3 * 9.81 * math.sqrt(2) / 3, rel=1e-9)
    foot0 = r["joints"][0]
    np.testing.assert_allclose(foot0["force"], [0, -9.81, 9.81], atol=1e-9)
    with pytest.raises(ValueError):
        ccma.statics(problem, wrench=[1, 2, 3])


def test_matches_the_command_line():
    model = ROOT / "models" / "4dof_reduced.yaml"
    cli = run_tool("statics", f"--model={model}", "--wrench=1,2,-20,0.1,0,0")
    r = ccma.statics(ccma.ForwardProblem(ccma.load_model(model)), wrench=[1, 2, -20, 0.1, 0, 0])
    for a, b in zip(r["actuators"], cli["actuators"]):
        assert a["name"] == b["name"] and a["kind"] == b["kind"]
        assert a["effort"] == pytest.approx(b["effort"], abs=1e-9)
    np.testing.assert_allclose(r["ee_covariance"], cli["ee_covariance"], atol=1e-15)
