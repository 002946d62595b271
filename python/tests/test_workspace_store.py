"""Sweeps that survive (issue 28): a map resumed from its store after the client
was killed mid-run, a damaged tile computed again, a worker killed mid-run, a
scheduler and two workers started from the command line, and a store of another
map refused. Every map must equal the one computed in one go on one thread,
sample by sample."""
import json
import os
import signal
import subprocess
import sys
import time

import pytest

import ccma
from conftest import ROOT, plant_pickled_array

pytest.importorskip("zarr")
MODEL = str(ROOT / "models" / "4dof_reduced.yaml")
# 24 x 24 = 576 samples in 16 tiles of 6 x 6 cells, about half reachable.
MAP = dict(ranges={"x": (-0.35, 0.35), "z": (0.35, 1.0)}, resolution=24, tile_size=6)


@pytest.fixture(scope="module")
def reference():
    return ccma.workspace(MODEL, threads=1, **MAP)


def assert_same_map(a, b):
    assert a.table == b.table and a.details == b.details


def python_env():
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT / "build" / "python"), env.get("PYTHONPATH", "")) if p)
    for path in sys.path:  # the module the tests import, wherever CTest put it
        if os.path.isdir(os.path.join(path, "ccma")) and os.path.exists(os.path.join(path, "ccma", "workspace.py")):
            env["PYTHONPATH"] = path + os.pathsep + env["PYTHONPATH"]
            break
    return env


KILLED_CLIENT = """
import os, signal, sys
import ccma
args = {args}
def progress(done, total):
    if done >= total // 3:  # a third of the map is in the store: the client dies here
        os.kill(os.getpid(), signal.SIGKILL)
ccma.workspace({model!r}, threads=2, store={store!r}, progress=progress, **args)
"""


def test_a_client_killed_mid_run_resumes_from_its_store(tmp_path, reference):
    store = str(tmp_path / "map.zarr")
    script = KILLED_CLIENT.format(args=repr(MAP), model=MODEL, store=store)
    run = subprocess.run([sys.executable, "-c", script], env=python_env(), capture_output=True, timeout=300)
    assert run.returncode == -signal.SIGKILL, run.stderr.decode()
    resumed = ccma.workspace(MODEL, threads=2, store=store, **MAP)
    assert_same_map(reference, resumed)
    assert 0 < resumed.tiles_from_store < resumed.tiles == 16
    # Run again: everything comes from the store, nothing is computed.
    again = ccma.workspace(MODEL, threads=1, store=store, **MAP)
    assert again.tiles_from_store == 16
    assert_same_map(reference, again)


def test_a_store_with_a_pickled_array_is_refused_without_running_it(tmp_path, reference):
    """issue 34: a tile whose array is a pickled object array (zarr would
    unpickle it on reading, running its code) stops the resume with a
    ValueError naming the store and the array; the code never runs."""
    store, marker = tmp_path / "map.zarr", tmp_path / "marker"
    ccma.workspace(MODEL, threads=1, store=str(store), **MAP)
    plant_pickled_array(store, 3, "reachable", marker)
    with pytest.raises(ValueError, match=r"map\.zarr': array chunks/3/reachable: dtype '\|O'"):
        ccma.workspace(MODEL, threads=1, store=str(store), **MAP)
    assert not marker.exists()


def test_a_damaged_tile_is_computed_again(tmp_path, reference):
    store = tmp_path / "map.zarr"
    ccma.workspace(MODEL, threads=1, store=str(store), **MAP)
    chunk = [p for p in (store / "chunks" / "5" / "reachable").iterdir() if not p.name.startswith(".")]
    assert chunk
    chunk[0].write_bytes(b"\x00" * 7)  # truncated garbage where the compressed block was
    resumed = ccma.workspace(MODEL, threads=1, store=str(store), **MAP)
    assert resumed.tiles_from_store == 15
    assert_same_map(reference, resumed)


def test_a_store_of_another_map_is_refused(tmp_path):
    store = str(tmp_path / "map.zarr")
    ccma.workspace(MODEL, threads=1, store=store, **dict(MAP, resolution=8))
    with pytest.raises(ValueError, match="holds another batch"):
        ccma.workspace(MODEL, threads=1, store=store, **dict(MAP, resolution=9))
    with pytest.raises(TypeError, match="path"):
        ccma.workspace(ccma.load_model(MODEL), store=store, **MAP)


@pytest.mark.parametrize("keep_root_attrs", [True, False], ids=["with-zattrs", "zattrs-deleted"])
def test_chunks_of_another_map_are_computed_again(tmp_path, keep_root_attrs):
    """issue 49: every chunk of a map made over z 0.4:1.05 instead of 0.35:1.0
    (the same tiles and sizes, each chunk whole with its sha256) copied into
    this map's store, with the store's root .zattrs kept or deleted: each is
    computed again with a warning naming it, and the map is this map's."""
    import shutil
    small = dict(MAP, resolution=12)  # 4 tiles of 6 x 6
    other_map = dict(small, ranges={"x": (-0.35, 0.35), "z": (0.4, 1.05)})
    mine, theirs = tmp_path / "mine.zarr", tmp_path / "theirs.zarr"
    want = ccma.workspace(MODEL, threads=1, store=str(mine), **small)
    other = ccma.workspace(MODEL, threads=1, store=str(theirs), **other_map)
    assert want.tiles == other.tiles == 4 and want.table != other.table
    for k in range(4):
        shutil.rmtree(mine / "chunks" / str(k))
        shutil.copytree(theirs / "chunks" / str(k), mine / "chunks" / str(k))
    if not keep_root_attrs:
        (mine / ".zattrs").unlink()
    with pytest.warns(UserWarning) as said:
        resumed = ccma.workspace(MODEL, threads=1, store=str(mine), **small)
    lines = sorted(str(w.message) for w in said)
    assert lines == [f"store {str(mine)!r}: chunks/{k} belongs to another batch (another map or sweep, or an older "
                     "ccma: its key is not this store's); computing it again" for k in range(4)]
    assert resumed.tiles_from_store == 0
    assert_same_map(want, resumed)
    again = ccma.workspace(MODEL, threads=1, store=str(mine), **small)  # written again as this map's
    assert again.tiles_from_store == 4
    assert_same_map(want, again)


def test_a_worker_killed_mid_run_is_survived(tmp_path, reference):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        pids = client.run(os.getpid)
        victim = sorted(pids.values())[0]
        killed = []

        def progress(done, total):
            if not killed and done >= total // 4:
                os.kill(victim, signal.SIGKILL)  # the nanny starts a new worker; Dask retries its tasks
                killed.append(done)

        store = str(tmp_path / "map.zarr")
        remote = ccma.workspace(MODEL, client=client, progress=progress, store=store, **MAP)
        assert killed
        assert_same_map(reference, remote)
        assert remote.tiles_from_store == 0


def test_a_scheduler_and_two_workers_from_the_command_line(tmp_path, reference):
    distributed = pytest.importorskip("distributed")
    scheduler_file = tmp_path / "scheduler.json"
    env = python_env()
    procs = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                               "--port", "0", "--dashboard-address", ":0", "--scheduler-file", str(scheduler_file)],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        deadline = time.time() + 60
        while not scheduler_file.exists() and time.time() < deadline:
            time.sleep(0.2)
        assert scheduler_file.exists()
        for _ in range(2):
            procs.append(subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", "--nthreads", "1",
                                           "--nworkers", "1", "--no-dashboard", "--scheduler-file",
                                           str(scheduler_file)],
                                          env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        with distributed.Client(scheduler_file=str(scheduler_file), timeout=60) as client:
            client.wait_for_workers(2, timeout=120)
            assert len(client.scheduler_info()["workers"]) == 2
            assert_same_map(reference, ccma.workspace(MODEL, client=client, **MAP))
    finally:
        for p in reversed(procs):
            p.send_signal(signal.SIGTERM)
        for p in procs:
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                p.kill()


def test_progress_bar_reports_samples(capsys):
    pytest.importorskip("tqdm")
    ccma.workspace(MODEL, threads=1, progress=True, **dict(MAP, resolution=8))
    err = capsys.readouterr().err
    assert "100%" in err and "64" in err and "sample/s" in err


def test_the_command_line_store_resumes_after_ctrl_c(tmp_path):
    from conftest import tool_path
    store, ranges = tmp_path / "store", ["--x=-0.35:0.35", "--z=0.35:1.0", "--resolution=40", "--tile_size=8"]
    whole = subprocess.run([tool_path(), "workspace", f"--model={MODEL}", f"--out={tmp_path / 'whole.csv'}", *ranges],
                           capture_output=True, timeout=300)
    assert whole.returncode == 0, whole.stderr.decode()
    command = [tool_path(), "workspace", f"--model={MODEL}", f"--out={tmp_path / 'map.csv'}", f"--store={store}", *ranges]
    run = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.time() + 120
    while time.time() < deadline and len(list(store.glob("tile_*.bin"))) < 3 and run.poll() is None:
        time.sleep(0.005)
    run.send_signal(signal.SIGINT)  # Ctrl-C: the tiles finished so far stay in the store
    out, err = run.communicate(timeout=60)
    assert run.returncode == -signal.SIGINT and out == b""  # a shell's exit status 130
    kept = len(list(store.glob("tile_*.bin")))
    assert 3 <= kept < 25 and not (tmp_path / "map.csv").exists()
    # stderr: the tiles the store keeps, and the command that resumes (this one).
    said = err.decode()
    assert said.startswith(f"ccma workspace: interrupted: {kept} of 25 tiles of the map are finished and kept"), said
    assert said.endswith("the same command again resumes from them:\n  " + " ".join(command) + "\n"), said
    resumed = subprocess.run(command, capture_output=True, timeout=300)
    assert resumed.returncode == 0, resumed.stderr.decode()
    summary = json.loads(resumed.stdout)
    assert summary["tiles"] == 25 and kept <= summary["tiles_from_store"] < 25
    assert (tmp_path / "map.csv").read_bytes() == (tmp_path / "whole.csv").read_bytes()
    # A damaged tile file is computed again; another map in the same store is refused.
    victim = sorted(store.glob("tile_*.bin"))[0]
    victim.write_bytes(victim.read_bytes()[:-9] + b"x")
    again = subprocess.run(command, capture_output=True, timeout=300)
    assert again.returncode == 0 and json.loads(again.stdout)["tiles_from_store"] == 24
    assert b"is damaged" in again.stderr
    assert (tmp_path / "map.csv").read_bytes() == (tmp_path / "whole.csv").read_bytes()
    other = subprocess.run(command[:-1] + ["--tile_size=4"], capture_output=True, timeout=300)
    assert other.returncode == 2 and other.stdout == b"" and b"holds another map" in other.stderr
