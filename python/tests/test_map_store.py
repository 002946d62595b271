"""The store of finished chunks (python/ccma/map_store.py): a chunk round-trips
exactly; a chunk without its completion marker (a writer killed mid-write) and a
chunk whose bytes were damaged both read as missing; a store made for other
arguments is refused."""
import glob
import os

import numpy as np
import pytest

pytest.importorskip("zarr")
from ccma.map_store import MapStore  # noqa: E402


def chunk(seed):
    rng = np.random.default_rng(seed)
    return {"poses": rng.normal(size=(5, 6)), "reachable": rng.random(5) > 0.5,
            "controls": np.zeros((0, 9)), "warning": ["", "stopped by a limit", "", "", ""]}


def test_a_chunk_round_trips_exactly(tmp_path):
    store = MapStore(tmp_path / "s.zarr", {"model": "m", "resolution": 11}, num_chunks=3)
    assert store.done() == set()
    store.write(1, chunk(1))
    again = MapStore(tmp_path / "s.zarr", {"resolution": 11, "model": "m"}, num_chunks=3)
    assert again.done() == {1}
    got, want = again.read(1), chunk(1)
    assert set(got) == set(want)
    for key in want:
        assert np.array_equal(np.asarray(got[key]), np.asarray(want[key])), key
    assert got["poses"].dtype == np.float64 and got["reachable"].dtype == bool
    assert again.read(0) is None and again.read(2) is None


def test_a_half_written_chunk_is_not_done(tmp_path):
    store = MapStore(tmp_path / "s.zarr", {"k": 1}, num_chunks=2)
    store.write(0, chunk(2))
    # What a writer killed before its marker leaves: the arrays, no "complete".
    store._chunks["0"].attrs["complete"] = False
    assert store.done() == set() and store.read(0) is None
    store.write(0, chunk(2))
    assert store.done() == {0} and np.array_equal(store.read(0)["poses"], chunk(2)["poses"])


def test_a_damaged_chunk_reads_as_missing(tmp_path):
    path = tmp_path / "s.zarr"
    store = MapStore(path, {"k": 1}, num_chunks=2)
    store.write(1, chunk(3))
    data = [f for f in glob.glob(str(path / "chunks" / "1" / "poses" / "*")) if not os.path.basename(f).startswith(".")]
    assert data
    with open(data[0], "r+b") as f:  # flip bytes in the compressed block
        raw = bytearray(f.read())
        raw[len(raw) // 2] ^= 0xFF
        f.seek(0)
        f.write(raw)
    assert store.read(1) is None


def test_a_store_of_other_arguments_is_refused(tmp_path):
    MapStore(tmp_path / "s.zarr", {"resolution": 11}, num_chunks=4)
    with pytest.raises(ValueError, match="holds another batch"):
        MapStore(tmp_path / "s.zarr", {"resolution": 12}, num_chunks=4)
    with pytest.raises(ValueError, match="holds another batch"):
        MapStore(tmp_path / "s.zarr", {"resolution": 11}, num_chunks=5)
