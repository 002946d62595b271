"""ccma.workspace and ccma.design bound their work by its estimated cost, as
`ccma workspace` and `ccma design` do (issue 49 items 11 and 12;
docs/security.md, "Work bounded by its cost"): a run estimated beyond
max_minutes raises ccma.WorkBoundError within seconds, naming the estimate
and the max_minutes that would allow it; a long run says its estimate and
progress on sys.stderr; within the bound nothing changes."""
import re

import pytest

import ccma
from conftest import ROOT, run_tool

MODEL = str(ROOT / "models" / "4dof_reduced.yaml")
MILLION = {"x": (-0.5, 0.5), "z": (0.4, 1.0)}  # with resolution=1000


def compliant_model(tmp_path, agents):
    """`ccma generate --agents=N`, a mass on every body and springs on every
    base and spherical joint (tests/work_bound_cli_test.cc CompliantModel)."""
    plain, out = tmp_path / "plain.yaml", tmp_path / "compliant.yaml"
    run_tool("generate", "--agents=%d" % agents, "--out=%s" % plain)
    text = plain.read_text()
    text = re.sub(r"(- \{name: \w+, position: \[[^\]]*\])\}", r"\1, mass: 1}", text)
    text = re.sub(r"(pose: \[[^\]]*\])\}", r"\1, stiffness: [1.0e5, 1.0e5, 1.0e3]}", text)
    text = text.replace("- {type: spherical, ", "- {type: spherical, stiffness: {translation: 1.0e7}, ")
    out.write_text(text)
    return str(out)


def refused(error, function, work):
    text = str(error.value)
    assert text.startswith("ccma.%s: about " % function), text
    assert work in text, text
    assert re.search(r"allows: give max_minutes=[0-9]+ or more to run it", text), text


def test_a_million_samples_beyond_the_bound_are_refused_on_local_threads(capsys):
    with pytest.raises(ccma.WorkBoundError) as error:
        ccma.workspace(MODEL, MILLION, resolution=1000, max_minutes=0.5)
    refused(error, "workspace", "for 1,000,000 samples (")
    assert isinstance(error.value, ValueError)


def test_a_million_samples_beyond_the_bound_are_refused_tile_by_tile(tmp_path):
    # With a store the tiles are counted in Python as they are placed.
    with pytest.raises(ccma.WorkBoundError) as error:
        ccma.workspace(MODEL, MILLION, resolution=1000, max_minutes=0.5, store=str(tmp_path / "store"))
    refused(error, "workspace", "for 1,000,000 samples (")


def test_a_thousand_design_iterations_of_the_deflection_objective_are_refused(tmp_path):
    targets = [[0, 0, 0.6, 0, 0, 0], [0.02, 0.01, 0.61, 0, 0, 0]]
    with pytest.raises(ccma.WorkBoundError) as error:
        ccma.design(compliant_model(tmp_path, 24), targets, vary=["joint2.point", "joint5.point", "joint8.point"],
                    max_change=0.1, objective="deflection", design_iterations=1000, max_minutes=1)
    refused(error, "design", "for up to 1,000 design iterations of the deflection objective (")


def test_the_bound_has_a_range_and_a_short_run_says_nothing(capsys):
    for bad in (0, -1, 10081, float("nan")):
        with pytest.raises(ValueError, match="max_minutes"):
            ccma.workspace(MODEL, {"z": (0.5, 0.7)}, resolution=5, max_minutes=bad)
    m = ccma.workspace(MODEL, {"z": (0.5, 0.7)}, resolution=5, max_minutes=0.1)
    assert m.samples == 5
    assert capsys.readouterr().err == ""
