"""ccma.workspace on a compliant model: the stiffness_min_N_per_m column, sample by sample
the tool's CSV (1 / statics' most_compliant, 0 where unreachable), the same through a store's
tiles; a rigid model's map has no such column."""
import csv

import numpy as np
import pytest

import ccma
from conftest import ROOT, run_tool

COMPLIANT = str(ROOT / "examples" / "statics" / "stewart_gough_compliant.yaml")
RIGID = str(ROOT / "models" / "4dof_reduced.yaml")
# z up to 0.75 m: beyond the legs' 0.1 m stroke, so some samples are unreachable.
RANGES = {"x": (-0.05, 0.05), "z": (0.45, 0.75)}


def test_compliant_map_has_the_tools_stiffness_column(tmp_path):
    m = ccma.workspace(COMPLIANT, RANGES, resolution=3)
    t = m.table
    assert "stiffness_min_N_per_m" in t.names
    stiffness, reachable = t["stiffness_min_N_per_m"], t["reachable"]
    assert 0 < reachable.sum() < len(reachable)
    assert np.all(stiffness[~reachable] == 0) and np.all(stiffness[reachable] > 5e4)
    out = tmp_path / "w.csv"
    run_tool("workspace", "--model=" + COMPLIANT, "--out=" + str(out), "--x=-0.05:0.05", "--z=0.45:0.75",
             "--resolution=3")
    with open(out) as f:
        rows = list(csv.DictReader(f))
    np.testing.assert_allclose([float(r["stiffness_min_N_per_m"]) for r in rows], stiffness, rtol=1e-12, atol=0)
    # Per reached sample: 1 / `ccma statics`' most_compliant at its controls.
    for i in np.flatnonzero(reachable)[:3]:
        u = ",".join(repr(float(v)) for v in t.stack([f"u{k}" for k in range(6)])[i])
        most = run_tool("statics", "--model=" + COMPLIANT, "--controls=" + u)["most_compliant"]["compliance"]
        assert stiffness[i] * most == pytest.approx(1, rel=1e-9)


def test_store_tiles_give_the_same_column(tmp_path):
    pytest.importorskip("zarr")
    local = ccma.workspace(COMPLIANT, RANGES, resolution=3)
    stored = ccma.workspace(COMPLIANT, RANGES, resolution=3, store=str(tmp_path / "map.zarr"))
    assert local.table == stored.table


def test_rigid_map_has_no_stiffness_column():
    t = ccma.workspace(RIGID, {"z": (0.5, 0.7)}, resolution=3).table
    assert not any("stiffness" in name for name in t.names)
