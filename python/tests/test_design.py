"""Design parameters from Python (docs/design.md): dX_EE/dp against central
differences of forward problems re-solved on edited model texts, and the
4-DOF example of `ccma design` (targets above the bundled z-range)."""
import numpy as np
import pytest

import ccma
from conftest import ROOT, plant_pickled_array, run_tool

MODEL_PATH = ROOT / "models" / "4dof_reduced.yaml"
POST_TOP = "point: [0, 0.583012702, 0.35]"  # joint1, the top of post0


def model_with_post_top(z):
    text = MODEL_PATH.read_text()
    assert text.count(POST_TOP) == 1
    return ccma.load_model_from_string(text.replace(POST_TOP, "point: [0, 0.583012702, %.17g]" % z))


def test_end_effector_sensitivity_matches_re_solved_differences():
    model = ccma.load_model(str(MODEL_PATH))
    control = ccma.ControlProblem(model)
    p = model.end_effector.p_W_home
    assert control.move_to([p[0] + 0.02, p[1] - 0.01, p[2] + 0.015, 0, 0, 0.02]).converged
    state, u = control.forward.state, control.controls
    sens = ccma.design_parameter_sensitivity(model, state, u, vary=["joint1.z"])
    assert sens["parameters"] == ["joint1.z"]
    assert sens["ds_dp"].shape == (model.state_size, 1)
    h = 1e-5
    sides = []
    for z in (0.35 + h, 0.35 - h):
        forward = ccma.ForwardProblem(model_with_post_top(z))
        forward.set_state(state)
        assert forward.solve(u).converged
        sides.append(forward.end_effector.position)
    dX = (sides[0] - sides[1]) / (2 * h)
    assert np.abs(dX).max() > 1e-2  # the post top really moves the end-effector
    assert np.abs(sens["dX_dp"][:3, 0] - dX).max() < 1e-6 * np.abs(dX).max()


def test_design_makes_high_targets_reachable():
    model = ccma.load_model(str(MODEL_PATH))
    targets = np.array([[w.position[0], w.position[1], w.position[2], w.rpy[0], w.rpy[1], w.rpy[2]]
                        for w in ccma.load_waypoints(str(ROOT / "models" / "targets" / "4dof_high_z.csv"))])
    r = ccma.design(model, targets, vary=["joint1.z", "joint4.z", "joint7.z"])
    assert r.converged, r.warning
    assert not r.reached_before.any()
    assert all(t.reached and t.min_singular_value >= 0.02 for t in r.targets)
    assert all(c.new > c.old + 0.1 and c.unit == "m" for c in r.changed)  # the posts were raised
    for target in targets:  # a separate controller on the designed model
        control = ccma.ControlProblem(r.new_model)
        result = control.move_to(target)
        assert result.converged and result.error < 1e-6


def test_unknown_names_are_value_errors():
    model = ccma.load_model(str(MODEL_PATH))
    with pytest.raises(ValueError, match="nosuch"):
        ccma.design(model, np.zeros((1, 6)), vary=["nosuch.z"])
    with pytest.raises(ValueError, match="vary"):
        ccma.design(model, np.zeros((1, 6)))


def high_targets():
    return np.array([[w.position[0], w.position[1], w.position[2], w.rpy[0], w.rpy[1], w.rpy[2]]
                     for w in ccma.load_waypoints(str(ROOT / "models" / "targets" / "4dof_high_z.csv"))])


GRID = {"joint1.z": [0.35, 0.6], "joint4.z": [0.35, 0.6], "joint7.z": [0.35, 0.6]}


def test_design_sweep_finds_the_raised_posts_locally():
    sweep = ccma.design_sweep(str(MODEL_PATH), GRID, high_targets(), chunk_size=3)
    table = sweep.table
    assert len(sweep) == len(table) == 8 and sweep.parameters == list(GRID)
    assert table.names == list(GRID) + ["all_reached", "min_singular_value", "feasible"]
    assert table["joint7.z"][:2].tolist() == [0.35, 0.6]  # last name fastest
    assert not table["all_reached"][0]  # the bundled model
    assert table["feasible"][-1]        # all three posts raised by 0.25 m
    assert sweep.reached.shape == (8, 3) and sweep.reached.dtype == bool
    # The sweep agrees with evaluate_design on the same candidate.
    direct = ccma.evaluate_design(ccma.load_model(str(MODEL_PATH)), high_targets(), [0.6, 0.6, 0.6],
                                  vary=["joint1.z", "joint4.z", "joint7.z"])
    assert [r["reached"] for r in direct] == sweep.reached[-1].tolist()
    assert sweep.to_records()[-1]["feasible"] is True


def test_design_sweep_on_dask_workers_equals_the_local_run():
    distributed = pytest.importorskip("distributed")
    local = ccma.design_sweep(str(MODEL_PATH), GRID, high_targets(), chunk_size=3)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        remote = ccma.design_sweep(str(MODEL_PATH), GRID, high_targets(), client=client, chunk_size=3)
    assert remote == local


def test_design_sweep_called_again_and_again_on_one_client():
    # The model text used to be scattered under a key hashed from its content:
    # every call shared it, and the release of an earlier call's copy cancelled
    # a later call's tasks (CancelledError in some of ten calls). A fresh key per
    # call (as ccma.workspace scatters) leaves each call its own copy.
    distributed = pytest.importorskip("distributed")
    grid = {"joint1.z": [0.35, 0.6]}
    targets = high_targets()[:1]
    local = ccma.design_sweep(str(MODEL_PATH), grid, targets, chunk_size=1)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        for _ in range(10):
            assert ccma.design_sweep(str(MODEL_PATH), grid, targets, client=client, chunk_size=1) == local
    assert local.table["joint1.z"].tolist() == [0.35, 0.6]


def test_design_sweep_refuses_a_store_with_a_pickled_array(tmp_path):
    """issue 34: design_sweep reads its store as data: a pickled object array
    is refused (ValueError naming the store and the array), never unpickled."""
    pytest.importorskip("zarr")
    store, marker = tmp_path / "sweep.zarr", tmp_path / "marker"
    grid = {"joint1.z": [0.35, 0.6]}
    ccma.design_sweep(str(MODEL_PATH), grid, high_targets()[:1], chunk_size=1, store=str(store))
    plant_pickled_array(store, 1, "reached", marker)
    with pytest.raises(ValueError, match=r"sweep\.zarr': array chunks/1/reached: dtype '\|O'"):
        ccma.design_sweep(str(MODEL_PATH), grid, high_targets()[:1], chunk_size=1, store=str(store))
    assert not marker.exists()
    # A chunk of plain arrays whose sha256 and store key match but whose shape is
    # not the sweep's (1 candidate x 1 target): written on purpose, refused.
    import json
    import zarr
    from ccma.map_store import MapStore
    forged = MapStore.__new__(MapStore)
    forged.path, forged.num_chunks = str(store), 2
    forged._key = json.loads((store / ".zattrs").read_text())["key"]  # the store's own, as a forger reads it
    forged._chunks = zarr.open_group(str(store / "chunks"), mode="a")
    forged.write(1, {k: np.zeros((1, 3)) for k in ("reached", "error", "min_singular_value", "within_limits")})
    with pytest.raises(ValueError, match=r"sweep\.zarr': chunk 1 does not hold 1 candidates x 1 targets"):
        ccma.design_sweep(str(MODEL_PATH), grid, high_targets()[:1], chunk_size=1, store=str(store))


def test_design_sweep_resumes_from_its_store_and_survives_a_lost_worker(tmp_path):
    """An interrupted sweep resumes from its store (the chunks done are not run
    again); a worker killed mid-sweep is survived; both equal the local run."""
    pytest.importorskip("zarr")
    local = ccma.design_sweep(str(MODEL_PATH), GRID, high_targets(), chunk_size=2)
    store = str(tmp_path / "sweep.zarr")

    class Interrupted(Exception):
        pass

    def stop_after_two_chunks(done, total):
        if done >= 4:
            raise Interrupted()

    with pytest.raises(Interrupted):
        ccma.design_sweep(str(MODEL_PATH), GRID, high_targets(), chunk_size=2, store=store,
                          progress=stop_after_two_chunks)
    seen = []
    resumed = ccma.design_sweep(str(MODEL_PATH), GRID, high_targets(), chunk_size=2, store=store,
                                progress=lambda done, total: seen.append(done))
    assert resumed == local
    assert seen == [6, 8]  # two chunks were read back, two computed
    with pytest.raises(ValueError, match="holds another batch"):
        ccma.design_sweep(str(MODEL_PATH), GRID, high_targets(), chunk_size=4, store=store)

    distributed = pytest.importorskip("distributed")
    import os
    import signal
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        victim = sorted(client.run(os.getpid).values())[0]
        killed = []

        def kill_a_worker(done, total):
            if not killed:
                os.kill(victim, signal.SIGKILL)
                killed.append(done)

        remote = ccma.design_sweep(str(MODEL_PATH), GRID, high_targets(), client=client, chunk_size=1,
                                   progress=kill_a_worker)
    assert killed and remote == local


def test_design_inputs_beyond_the_cli_bounds_are_refused(tmp_path):
    """issue 34: targets are held to `ccma design --targets` (1 to 1000 rows within
    1e4), and a sweep's grid is counted before it is expanded (at most 1e6
    candidates of finite values): refused before anything runs."""
    import math
    model = ccma.load_model(str(MODEL_PATH))
    far = np.array([[0, 0, 1e5, 0, 0, 0]])
    with pytest.raises(ValueError, match=r"targets: N x 6 finite numbers within \[-1e4, 1e4\]"):
        ccma.evaluate_design(model, far, [0.5], vary=["joint1.z"])
    with pytest.raises(ValueError, match=r"1 <= N <= 1000 \(got 1001 rows\)"):
        ccma.design(model, np.zeros((1001, 6)), vary=["joint1.z"])
    with pytest.raises(ValueError, match=r"the grid has 1000000000000 candidates; at most 1000000"):
        ccma.design_sweep(str(MODEL_PATH), {f"joint{i}.z": np.linspace(0.3, 0.6, 1000) for i in (1, 4, 7, 10)},
                          high_targets())
    with pytest.raises(ValueError, match=r"parameter_grid\['joint1.z'\]: 'nan' is not a finite number"):
        ccma.design_sweep(str(MODEL_PATH), {"joint1.z": [0.35, math.nan]}, high_targets())
    with pytest.raises(ValueError, match=r"design_sweep: targets must be 1 to 1000 rows"):
        ccma.design_sweep(str(MODEL_PATH), {"joint1.z": [0.35]}, far)


def test_design_sweep_reads_its_model_through_the_bounded_reader(tmp_path):
    """A FIFO given as the model is refused (ModelError, 'not a regular file')
    instead of being opened, which blocked until a writer came."""
    import os
    import threading
    fifo = tmp_path / "model.yaml"
    os.mkfifo(fifo)

    def feed():  # what a writer would send, should the FIFO be opened for reading
        for _ in range(300):
            try:
                fd = os.open(fifo, os.O_WRONLY | os.O_NONBLOCK)
            except OSError:  # no reader yet
                threading.Event().wait(0.01)
                continue
            with os.fdopen(fd, "w") as f:
                f.write(MODEL_PATH.read_text())
            return

    writer = threading.Thread(target=feed)
    writer.start()
    try:
        with pytest.raises(ccma.ModelError, match="not a regular file"):
            ccma.design_sweep(str(fifo), {"joint1.z": [0.35]}, high_targets()[:1])
    finally:
        writer.join()


def test_stiffness_objective_matches_the_tool(tmp_path):
    model = str(ROOT / "examples" / "statics" / "stewart_gough_compliant.yaml")
    targets = str(ROOT / "examples" / "statics" / "stewart_gough_compliant_targets.csv")
    vary = ["joint%d.point" % j for j in (0, 3, 6, 9, 12, 15)]
    r = ccma.design(model, targets, vary=vary, max_change=0.1, objective="stiffness", out=tmp_path / "py.yaml")
    cli = run_tool("design", "--model=" + model, "--targets=" + targets, "--vary=" + ",".join(vary),
                   "--max_change=0.1", "--objective=stiffness", "--out=" + str(tmp_path / "cli.yaml"))
    assert r.objective["unit"] == "m/N" and r.objective["after"]["value"] == cli["objective"]["after"]["value"]
    assert r.objective["after"]["value"] < 0.5 * r.objective["before"]["value"]
    assert (tmp_path / "py.yaml").read_bytes() == (tmp_path / "cli.yaml").read_bytes()
    with pytest.raises(ValueError, match="no stiffness keys"):
        ccma.design(str(ROOT / "models" / "4dof_reduced.yaml"), targets, vary=["joint0.x"], objective="deflection")
