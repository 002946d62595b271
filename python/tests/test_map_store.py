"""The store of finished chunks (python/ccma/map_store.py): a chunk round-trips
exactly; a chunk without its completion marker (a writer killed mid-write) and a
chunk whose bytes were damaged both read as missing; a store made for other
arguments is refused; a store holding what ccma never writes (a pickled object
array, links, FIFOs, oversized files) is refused before anything is decoded."""
import glob
import json
import os
import shutil

import numpy as np
import pytest

pytest.importorskip("zarr")
from ccma.map_store import MapStore  # noqa: E402
from conftest import plant_pickled_array  # noqa: E402


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


def test_a_store_reached_through_a_link_the_user_made_resumes(tmp_path):
    store = MapStore(tmp_path / "s.zarr", {"k": 1}, num_chunks=1)
    store.write(0, chunk(11))
    (tmp_path / "link.zarr").symlink_to(tmp_path / "s.zarr")
    again = MapStore(tmp_path / "link.zarr", {"k": 1}, num_chunks=1)
    assert again.done() == {0} and np.array_equal(again.read(0)["poses"], chunk(11)["poses"])


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


def test_a_chunk_of_another_store_is_computed_again_with_a_warning(tmp_path):
    """issue 49: a chunk is bound to its batch's key (inside its sha256): one
    copied from a store of other arguments reads as missing, with a warning,
    also when the store's own .zattrs was deleted; a chunk whose key alone was
    rewritten fails its sha256."""
    import shutil
    theirs = MapStore(tmp_path / "theirs.zarr", {"k": 2}, num_chunks=2)
    theirs.write(0, chunk(7))
    for keep in (True, False):
        path = tmp_path / f"mine_{keep}.zarr"
        MapStore(path, {"k": 1}, num_chunks=2).write(1, chunk(8))
        if not keep:
            (path / ".zattrs").unlink()
        shutil.copytree(tmp_path / "theirs.zarr" / "chunks" / "0", path / "chunks" / "0")
        store = MapStore(path, {"k": 1}, num_chunks=2)
        assert store.done() == {0, 1}
        with pytest.warns(UserWarning, match=r"chunks/0 belongs to another batch .*computing it again"):
            assert store.read(0) is None
        assert np.array_equal(store.read(1)["poses"], chunk(8)["poses"])  # its own chunk still reads back
        attrs = json.loads((path / "chunks" / "0" / ".zattrs").read_text())
        attrs["key"] = store._key  # the key forged, the sha256 left
        (path / "chunks" / "0" / ".zattrs").write_text(json.dumps(attrs))
        assert store.read(0) is None


# A store is data that may come from someone else (a shared cluster folder):
# read() checks every array's metadata before decoding a byte, and a store
# holding what ccma never writes is refused (ValueError naming the store and
# the array), never decoded and never silently computed again.

def test_a_pickled_object_array_is_refused_without_running_it(tmp_path):
    path, marker = tmp_path / "s.zarr", tmp_path / "marker"
    MapStore(path, {"k": 1}, num_chunks=2).write(0, chunk(4))
    plant_pickled_array(path, 0, "reachable", marker)
    store = MapStore(path, {"k": 1}, num_chunks=2)
    assert store.done() == {0}
    with pytest.raises(ValueError, match=r"store '.*s\.zarr': array chunks/0/reachable: dtype '\|O' is not a "
                                         r"plain bool, integer or float"):
        store.read(0)
    assert not marker.exists()


def rewrite_meta(path, change):
    meta = json.loads(path.read_text())
    change(meta)
    path.write_text(json.dumps(meta))


@pytest.mark.parametrize("change, message", [
    (lambda m: m.update(filters=[{"id": "zlib", "level": 1}]), "filters are set"),
    (lambda m: m.update(compressor={"id": "zstd", "level": 1}), "compressor is not blosc lz4"),
    (lambda m: m.update(dtype=">f8"), "dtype '>f8'"),
    (lambda m: m.update(dtype="<M8[ns]"), "dtype '<M8\\[ns\\]'"),
    (lambda m: m.update(chunks=[1, 6]), "not one chunk covering the array"),
    (lambda m: m.update(shape=[10 ** 12, 6], chunks=[10 ** 12, 6]), "more than 2147483631 bytes"),
    (lambda m: m.update(order="F"), "order is not C"),
    (lambda m: m.update(object_codec="pickle"), "unexpected .zarray keys"),
], ids=["filters", "zstd", "big-endian", "datetime", "chunks", "huge", "order", "extra-key"])
def test_array_metadata_ccma_never_writes_is_refused(tmp_path, change, message):
    path = tmp_path / "s.zarr"
    MapStore(path, {"k": 1}, num_chunks=1).write(0, chunk(5))
    rewrite_meta(path / "chunks" / "0" / "poses" / ".zarray", change)
    with pytest.raises(ValueError, match=r"array chunks/0/poses: " + message):
        MapStore(path, {"k": 1}, num_chunks=1).read(0)


def test_links_fifos_and_oversized_files_in_a_store_are_refused(tmp_path):
    path = tmp_path / "s.zarr"
    store = MapStore(path, {"k": 1}, num_chunks=4)
    for i in range(4):
        store.write(i, chunk(6 + i))
    (tmp_path / "secret").write_bytes(b"\x00" * 64)
    data = path / "chunks" / "0" / "poses" / "0.0"
    data.unlink()
    data.symlink_to(tmp_path / "secret")  # a chunk file that is a link
    with pytest.raises(ValueError, match=r"chunks/0/poses/0\.0 is not a regular file"):
        store.read(0)
    data = path / "chunks" / "1" / "reachable" / "0"
    data.unlink()
    os.mkfifo(data)  # would block a reader for ever
    with pytest.raises(ValueError, match=r"chunks/1/reachable/0 is not a regular file"):
        store.read(1)
    attrs = path / "chunks" / "2" / ".zattrs"
    with open(attrs, "r+b") as f:  # beyond the bound, sparse: nothing is read
        f.truncate((64 << 20) + 1)
    with pytest.raises(ValueError, match=r"chunks/2/\.zattrs has \d+ bytes; at most 67108864 are allowed"):
        store.done()
    attrs.write_text(json.dumps({"fields": ["../../1/poses"], "strings": {}, "sha256": "", "complete": True}))
    with pytest.raises(ValueError, match=r"chunks/2/\.zattrs is not what ccma writes"):
        store.read(2)
    shutil.rmtree(path / "chunks" / "3")
    (path / "chunks" / "3").symlink_to(path / "chunks" / "1")  # a chunk folder that is a link
    with pytest.raises(ValueError, match=r"chunks/3 is not a directory"):
        store.read(3)


def test_a_store_root_ccma_never_writes_is_refused(tmp_path):
    path = tmp_path / "s.zarr"
    MapStore(path, {"k": 1}, num_chunks=1).write(0, chunk(7))
    (path / ".zattrs").unlink()
    (path / ".zattrs").symlink_to("/dev/zero")
    with pytest.raises(ValueError, match=r"\.zattrs is not a regular file"):
        MapStore(path, {"k": 1}, num_chunks=1)
    (path / ".zattrs").unlink()
    (path / ".zgroup").write_text('{"zarr_format": 3}')
    with pytest.raises(ValueError, match=r"\.zgroup is not a Zarr format 2 group"):
        MapStore(path, {"k": 1}, num_chunks=1)
    (path / ".zgroup").write_text('{"zarr_format": 2}')
    shutil.move(str(path / "chunks"), str(tmp_path / "elsewhere"))
    (path / "chunks").symlink_to(tmp_path / "elsewhere")
    with pytest.raises(ValueError, match=r"chunks is not a directory"):
        MapStore(path, {"k": 1}, num_chunks=1)


def test_a_damaged_blosc_header_reads_as_missing(tmp_path):
    """A chunk whose header claims another size (1 GB from 40 bytes) is not
    allocated: it is damaged, computed again."""
    path = tmp_path / "s.zarr"
    store = MapStore(path, {"k": 1}, num_chunks=1)
    store.write(0, chunk(8))
    data = path / "chunks" / "0" / "poses" / "0.0"
    raw = bytearray(data.read_bytes())
    raw[4:8] = (1 << 30).to_bytes(4, "little")
    data.write_bytes(raw)
    assert store.read(0) is None
    store.write(0, chunk(8))
    assert np.array_equal(store.read(0)["poses"], chunk(8)["poses"])


def test_zero_dimensional_and_empty_arrays_round_trip(tmp_path):
    store = MapStore(tmp_path / "s.zarr", {"k": 1}, num_chunks=1)
    want = {"scalar": np.float64(2.5), "empty": np.zeros((0, 3)), "ints": np.arange(4, dtype=np.int32),
            "small": np.array([1, 2], dtype=np.uint8), "names": ["a", "b"]}
    store.write(0, want)
    got = MapStore(tmp_path / "s.zarr", {"k": 1}, num_chunks=1).read(0)
    for key in want:
        assert np.array_equal(np.asarray(got[key]), np.asarray(want[key])), key
        assert np.asarray(got[key]).dtype == np.asarray(want[key]).dtype, key


def test_a_link_planted_where_a_chunk_goes_is_not_written_through(tmp_path):
    path = tmp_path / "s.zarr"
    store = MapStore(path, {"k": 1}, num_chunks=2)
    store.write(0, chunk(9))
    victim = tmp_path / "victim"
    victim.mkdir()
    (path / "chunks" / "1").symlink_to(victim)
    store.write(1, chunk(10))
    assert list(victim.iterdir()) == []
    assert not (path / "chunks" / "1").is_symlink()
    assert np.array_equal(store.read(1)["poses"], chunk(10)["poses"])
