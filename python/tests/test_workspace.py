"""ccma.workspace: the C++ map from Python, against the `ccma workspace` tool and the
legs' reach, and on a Dask local cluster of two worker processes (same results)."""
import csv

import numpy as np
import pytest

import ccma
from conftest import ROOT, run_tool

MODEL = str(ROOT / "models" / "4dof_reduced.yaml")
# The legs of 4dof_reduced (0.5 m links from 0.35 m posts) reach up to z = 0.85 m.
# In the order x y z roll pitch yaw, as the tool takes them (the grid's first range varies slowest).
RANGES = {"x": (-0.2, 0.2), "z": (0.4, 1.1)}


def test_grid_matches_leg_reach_and_the_tool(tmp_path):
    m = ccma.workspace(MODEL, RANGES, resolution=8, threads=2)
    assert m["components"] == ["x", "z"]
    z = m["poses"][:, 2]
    assert len(z) == 64
    np.testing.assert_array_equal(m["reachable"], z < 0.85)
    assert np.all(m["residual_energy"][m["reachable"]] < 1e-20)
    assert np.all(m["sigma_min"][m["reachable"]] > 1e-3)
    assert np.all(m["sigma_min"][~m["reachable"]] == 0)
    # The tool gives the same rows (same waves and starts): controls to 1e-15 m.
    out = tmp_path / "w.csv"
    j = run_tool("workspace", "--model=" + MODEL, "--out=" + str(out), "--z=0.4:1.1", "--x=-0.2:0.2",
                 "--resolution=8")
    assert j["samples"] == 64 and j["reachable"] == int(m["reachable"].sum())
    with open(out) as f:
        rows = list(csv.DictReader(f))
    for i, row in enumerate(rows):
        assert float(row["z"]) == z[i]
        assert int(row["reachable"]) == int(m["reachable"][i])
        if m["reachable"][i]:
            u = np.array([float(row[f"u{k}"]) for k in range(9)])
            np.testing.assert_allclose(u, m["controls"][i], rtol=0, atol=1e-15)


def test_bad_arguments_raise():
    with pytest.raises(ValueError, match="roll is not a controlled"):
        ccma.workspace(MODEL, {"roll": (0, 1)})
    with pytest.raises(ValueError, match="threads"):
        ccma.workspace(MODEL, {"z": (0.4, 0.5)}, threads=0)
    with pytest.raises(ValueError, match="lo <= hi"):
        ccma.workspace(MODEL, {"z": (0.5, 0.4)})
    with pytest.raises(ValueError, match="resolution"):
        ccma.workspace(MODEL, {"z": (0.4, 0.5)}, resolution=2.5)
    with pytest.raises(TypeError, match="path"):
        ccma.workspace(ccma.load_model(MODEL), {"z": (0.4, 0.5)}, client=object())


def test_dask_local_cluster_gives_the_local_results():
    distributed = pytest.importorskip("distributed")
    kwargs = dict(samples=30, seed=3, wave_size=8)
    ranges = {"x": (-0.3, 0.3), "y": (-0.3, 0.3), "z": (0.45, 0.95)}
    local = ccma.workspace(MODEL, ranges, threads=1, **kwargs)
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        remote = ccma.workspace(MODEL, ranges, client=client, chunk_size=3, **kwargs)
        # A second call on the same client (the model text is scattered again).
        again = ccma.workspace(MODEL, ranges, client=client, chunk_size=7, **kwargs)
        np.testing.assert_array_equal(again["controls"], remote["controls"])
        # Each worker process loaded the model at most once.
        loaded = client.run(lambda: len(__import__("sys").modules["ccma.workspace"]._MODELS))
        assert sorted(loaded.values()) in ([0, 1], [1, 1])
    assert 0 < local["reachable"].sum() < 30
    for key in ("reachable", "controls", "residual_energy", "sigma_min", "rcond", "start", "wave", "poses"):
        np.testing.assert_array_equal(local[key], remote[key], err_msg=key)
    assert local["warning"] == remote["warning"]


def test_samples_too_many_path_steps_away_are_unreachable_not_an_error():
    # 2 km in steps of 10 mm is more than the 100,000 path steps of one walk.
    m = ccma.workspace(MODEL, {"x": (0.0, 2000.0), "z": (0.5, 0.75)}, resolution=2)
    np.testing.assert_array_equal(m["reachable"], [True, True, False, False])
    assert all("100000 steps" in w for w in m["warning"][2:])
    np.testing.assert_array_equal(m["steps"][2:], [0, 0])
