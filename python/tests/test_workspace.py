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
    t = m.table
    assert m.components == ["x", "z"] and t.names[:4] == ["x", "y", "z", "yaw"]  # the controlled components
    z, reachable = t["z"], t["reachable"]
    assert len(z) == m.samples == 64
    np.testing.assert_array_equal(reachable, z < 0.85)
    assert m.reachable == reachable.sum()
    assert np.all(t["residual_energy"][reachable] < 1e-20)
    assert np.all(t["sigma_min"][reachable] > 1e-3)
    assert np.all(t["sigma_min"][~reachable] == 0)
    # The tool gives the same rows (same waves and starts): controls to 1e-15 m.
    out = tmp_path / "w.csv"
    j = run_tool("workspace", "--model=" + MODEL, "--out=" + str(out), "--z=0.4:1.1", "--x=-0.2:0.2",
                 "--resolution=8")
    assert j["samples"] == 64 and j["reachable"] == m.reachable
    with open(out) as f:
        rows = list(csv.DictReader(f))
    for i, row in enumerate(rows):
        assert float(row["z"]) == z[i]
        assert int(row["reachable"]) == int(reachable[i])
        if reachable[i]:
            u = np.array([float(row[f"u{k}"]) for k in range(9)])
            np.testing.assert_allclose(u, t.stack([f"u{k}" for k in range(9)])[i], rtol=0, atol=1e-15)


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


def assert_same_map(a, b):
    assert a.table == b.table  # every column of the CSV, sample by sample (NaN where unreachable)
    assert a.details == b.details  # converged, assembled, steps, tile, warning
    assert a.tiles == b.tiles and a.tile_size == b.tile_size


def test_dask_local_cluster_gives_the_local_results():
    distributed = pytest.importorskip("distributed")
    # A grid in 16 tiles of 4 x 4 cells, and draws binned into 27 tiles.
    grid = dict(ranges={"x": (-0.4, 0.4), "z": (0.3, 1.2)}, resolution=16, tile_size=4)
    draws = dict(ranges={"x": (-0.3, 0.3), "y": (-0.3, 0.3), "z": (0.45, 0.95)}, samples=60, seed=3,
                 wave_size=8, tile_size=2)
    local = {name: ccma.workspace(MODEL, threads=1, **kw) for name, kw in (("grid", grid), ("draws", draws))}
    assert local["grid"].tiles == 16 and local["draws"].tiles > 4
    seen = []
    two = ccma.workspace(MODEL, threads=2, progress=lambda done, total: seen.append((done, total)), **grid)
    assert_same_map(local["grid"], two)
    assert seen[-1] == (256, 256) and all(a[0] <= b[0] for a, b in zip(seen, seen[1:]))
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        progress = []
        remote = ccma.workspace(MODEL, client=client, progress=lambda d, t: progress.append((d, t)), **grid)
        assert_same_map(local["grid"], remote)
        assert progress[-1] == (256, 256) and len(progress) == 16  # one call per tile
        # Groups of tiles per task and one task in flight: the same map.
        grouped = ccma.workspace(MODEL, client=client, chunk_size=3, max_in_flight=1, **grid)
        assert_same_map(local["grid"], grouped)
        # A second call on the same client (the model text is scattered again), on draws.
        assert_same_map(local["draws"], ccma.workspace(MODEL, client=client, chunk_size=2, **draws))
        # Each worker process loaded the model at most once.
        loaded = client.run(lambda: len(__import__("sys").modules["ccma.workspace"]._MODELS))
        assert sorted(loaded.values()) in ([0, 1], [1, 1])
    # z up to the legs' reach (0.85 m); the same count as one tile, the global continuation.
    assert local["grid"].reachable == 156
    single = ccma.workspace(MODEL, **dict(grid, tile_size=16))
    assert single.tiles == 1 and single.reachable == 156
    assert 0 < local["draws"].reachable < 60


def test_progress_and_chunk_arguments_are_checked():
    with pytest.raises(TypeError, match="progress"):
        ccma.workspace(MODEL, {"z": (0.4, 0.5)}, progress=3)
    with pytest.raises(ValueError, match="tile_size"):
        ccma.workspace(MODEL, {"z": (0.4, 0.5)}, tile_size=-1)
    with pytest.raises(ValueError, match="max_in_flight"):
        ccma.workspace(MODEL, {"z": (0.4, 0.5)}, max_in_flight=0)


def test_samples_too_many_path_steps_away_are_unreachable_not_an_error():
    # 2 km in steps of 10 mm is more than the 100,000 path steps of one walk.
    m = ccma.workspace(MODEL, {"x": (0.0, 2000.0), "z": (0.5, 0.75)}, resolution=2)
    np.testing.assert_array_equal(m.table["reachable"], [True, True, False, False])
    assert all("100000 steps" in w for w in m.details["warning"][2:])
    np.testing.assert_array_equal(m.details["steps"][2:], [0, 0])
