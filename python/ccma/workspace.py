"""Workspace maps from Python, on this machine or on a Dask cluster.

    import ccma
    m = ccma.workspace("models/4dof_reduced.yaml", {"z": (0.4, 1.0), "x": (-0.5, 0.5)},
                       resolution=25, threads=2)
    m.reachable, m.samples           # counts, as `ccma workspace` prints them
    m.table["reachable"]             # NumPy bool per sample; the CSV's columns: x, z, sigma_min, u0, ...

    from distributed import Client
    m = ccma.workspace(path, ranges, client=Client("tcp://scheduler:8786"),
                       progress=lambda done, total: print(done, "/", total))

The map is cut into tiles (C++, analyses/workspace.h). With a client, every
tile (or group of `chunk_size` ready tiles) is one task, sent as soon as the
tiles it depends on (its neighbours nearer home) are finished, with their
results: no barrier over the whole map, at most `max_in_flight` tasks in
flight, results placed in map order as they complete. The model
file's text is scattered to every worker once and loaded there once per
worker process (cached by its hash), so a distributed map equals the local
one exactly. Reference: docs/workspace.md, docs/python.md.
"""
import hashlib
import heapq
import os
import pickle
import time

import numpy as _np

from . import _ccma
from ._tables import Table, out_path
from .results import WorkspaceResult

_MODELS = {}  # per worker process: hash of the model text -> Model


def _model_on_worker(text):
    key = hashlib.sha256(text.encode("utf-8")).hexdigest()
    model = _MODELS.get(key)
    if model is None:
        model = _MODELS[key] = _ccma.load_model_from_string(text, "workspace model")
    return model


def _evaluate_tiles(text, args, control_kw, tiles, inputs):
    """Runs on a worker: whole tiles, one thread. inputs[k]: the results of the
    tiles that tiles[k] depends on. Results and inputs travel pickled (one dict
    per tile, with states): Dask passes bytes through without walking them, and
    the client forwards a result to the tiles that need it without pickling it
    again."""
    model = _model_on_worker(text)
    control = _ccma.ControlOptions(**control_kw)
    ranges, resolution, samples, seed, wave_size, tile_size = args
    out = []
    for t, given in zip(tiles, inputs):
        result = _ccma._workspace_tile(model, ranges, resolution, samples, seed, wave_size, control, tile_size,
                                       t, [pickle.loads(g) for g in given])
        out.append(pickle.dumps(result, protocol=pickle.HIGHEST_PROTOCOL))
    return out


def _place(out, rows, part, n):
    """Writes a tile's per-sample values at its map rows (states are left out)."""
    for key, values in part.items():
        if key in ("states", "carried", "carried_rows"):
            continue
        if key not in out:
            out[key] = [None] * n if isinstance(values, list) else _np.empty((n,) + values.shape[1:], values.dtype)
        if isinstance(values, list):
            for r, v in zip(rows, values):
                out[key][r] = v
        else:
            out[key][rows] = values


class _Schedule:
    """Which tiles are ready (the tiles they depend on finished), nearest home
    first, and the finished tiles' results that a tile not yet sent needs.
    Tiles in `preloaded` (read back from a store) finish as soon as they are
    ready, without being sent."""

    def __init__(self, tiles, preloaded=None, on_preloaded=None):
        self.tiles = tiles
        self.preloaded = dict(preloaded or {})
        self.on_preloaded = on_preloaded
        self.waiting = [len(t["depends_on"]) for t in tiles]
        self.users = [[] for _ in tiles]
        for t, tile in enumerate(tiles):
            for d in tile["depends_on"]:
                self.users[d].append(t)
        self.unsent_users = [len(u) for u in self.users]
        self.ready = [(tile["order"], t) for t, tile in enumerate(tiles) if not tile["depends_on"]]
        heapq.heapify(self.ready)
        self.results = {}  # finished tile -> its result, while a tile that needs it is unsent

    def take(self, count):
        """Up to `count` ready tiles to compute and, for each, the results of the
        tiles it depends on (ready preloaded tiles are finished on the way)."""
        group, inputs = [], []
        while self.ready and len(group) < count:
            _, t = heapq.heappop(self.ready)
            given = [self.results[d] for d in self.tiles[t]["depends_on"]]
            for d in self.tiles[t]["depends_on"]:
                self.unsent_users[d] -= 1
                if self.unsent_users[d] == 0:
                    del self.results[d]
            if t in self.preloaded:
                blob = self.preloaded.pop(t)
                self.on_preloaded(t, blob)
                self.finish(t, blob)
                continue
            group.append(t)
            inputs.append(given)
        return group, inputs

    def finish(self, t, result):
        if self.unsent_users[t] > 0:
            self.results[t] = result
        for u in self.users[t]:
            self.waiting[u] -= 1
            if self.waiting[u] == 0:
                heapq.heappush(self.ready, (self.tiles[u]["order"], u))


class _LocalRunner:
    """Tile groups on a local thread pool (the C++ side releases the GIL)."""

    def __init__(self, threads, text, args, control):
        from concurrent.futures import ThreadPoolExecutor
        self._pool = ThreadPoolExecutor(max_workers=threads)
        self._call = (text, args, dict(control))

    def submit(self, group, inputs, priority):
        del priority  # a pool has no priorities: groups run in the order sent
        return self._pool.submit(_evaluate_tiles, *self._call, group, inputs)

    def next_done(self, pending):
        from concurrent.futures import FIRST_COMPLETED, wait
        done, _ = wait(list(pending), return_when=FIRST_COMPLETED)
        future = next(iter(done))
        return future, future.result()

    def close(self):
        self._pool.shutdown(wait=True, cancel_futures=True)


class _DaskRunner:
    """Tile groups as Dask tasks; a lost worker's tasks run again (_dask_tasks)."""

    def __init__(self, client, text, args, control):
        from ._dask_tasks import DaskTasks
        self._call = (args, dict(control))
        self._tasks = DaskTasks(client, text)

    def submit(self, group, inputs, priority):
        return self._tasks.submit(_evaluate_tiles, *self._call, group, inputs, priority=priority)

    def next_done(self, pending):
        del pending
        return self._tasks.next_done()

    def close(self):
        pass


def _drive(runner, tiles, schedule, window, chunk, on_tile):
    """Sends ready tiles (at most `window` groups in flight) until every tile
    is finished; on_tile(t, blob) as each completes."""
    pending = {}

    def submit_ready():
        while len(pending) < window and schedule.ready:
            group, inputs = schedule.take(chunk)
            if not group:
                continue
            # Tiles nearer home first: more tiles wait for them.
            pending[runner.submit(group, inputs, -tiles[group[0]]["order"])] = group

    submit_ready()
    while pending:
        token, blobs = runner.next_done(pending)
        for t, blob in zip(pending.pop(token), blobs):
            on_tile(t, blob)
            schedule.finish(t, blob)
        submit_ready()


def _flatten(part):
    """A tile's result as flat arrays and string lists (what a store keeps)."""
    flat = {}
    for key, value in part.items():
        if key == "carried":
            flat.update({"carried." + k: v for k, v in value.items()})
        elif key == "carried_rows":
            flat[key] = _np.asarray(value, dtype=_np.int64)
        else:
            flat[key] = value
    return flat


def _unflatten(flat):
    part, carried = {}, {}
    for key, value in flat.items():
        if key.startswith("carried."):
            carried[key[len("carried."):]] = value
        elif key == "carried_rows":
            part[key] = [int(r) for r in value]
        else:
            part[key] = value
    part["carried"] = carried
    return part


class _Progress:
    """progress=: None/False nothing, True a bar (tqdm.auto: terminal or
    Jupyter; samples/s), or a callable progress(done, total)."""

    def __init__(self, progress):
        self._call = progress if callable(progress) else None
        self._want_bar = progress is True
        self._bar = None
        self._done = 0

    def __call__(self, done, total):
        if self._call is not None:
            self._call(done, total)
        if self._want_bar and self._bar is None:
            self._want_bar = False
            try:
                from tqdm.auto import tqdm  # Debian's python3-tqdm; without it, no bar
                self._bar = tqdm(total=total, unit="sample", unit_scale=True, desc="workspace", smoothing=0.1)
            except ImportError:
                pass
        if self._bar is not None:
            self._bar.update(done - self._done)
        self._done = done

    def close(self):
        if self._bar is not None:
            self._bar.close()


def _by_tiles(runner, model, text, args, control, chunk, window, store, progress, estimate):
    """The map tile by tile on `runner` (local threads or Dask): ready tiles
    sent at once, at most `window` groups in flight, each finished tile placed
    in map order and, with a store, written there; tiles already in the store
    are read back, not computed."""
    start = time.perf_counter()
    ranges, resolution, samples, seed, wave_size, tile_size = args
    tiles = _ccma._workspace_tiles(model, ranges, resolution, samples, seed, wave_size, tile_size)
    n = sum(len(t["rows"]) for t in tiles)
    out, counts = {}, {"done": 0, "stored": 0}
    kept = None
    if store is not None:
        from .map_store import MapStore
        key = {"map": "ccma.workspace", "model": text, "args": args, "control": dict(control), "tiles": len(tiles)}
        kept = MapStore(store, key, len(tiles))
    preloaded = {}
    for t in sorted(kept.done()) if kept is not None else ():
        flat = kept.read(t)
        if flat is not None:
            preloaded[t] = pickle.dumps(_unflatten(flat), protocol=pickle.HIGHEST_PROTOCOL)

    def place(t, blob, write):
        part = pickle.loads(blob)
        if write and kept is not None:
            kept.write(t, _flatten(part))
        part["ee_std_m"] = _ccma._workspace_ee_std(model, part["states"], part["controls"], part["reachable"])
        stiffness = _ccma._workspace_stiffness_min(model, part["states"], part["controls"], part["reachable"])
        if stiffness is not None:  # a compliant model only
            part["stiffness_min_N_per_m"] = stiffness
        _place(out, tiles[t]["rows"], part, n)
        counts["done"] += len(tiles[t]["rows"])
        counts["stored"] += 0 if write else 1
        estimate.update(counts["done"])  # may raise ccma.WorkBoundError
        progress(counts["done"], n)

    schedule = _Schedule(tiles, preloaded, lambda t, blob: place(t, blob, False))
    try:
        _drive(runner, tiles, schedule, window, chunk, lambda t, blob: place(t, blob, True))
    finally:
        runner.close()
    out["components"] = [r[0] for r in ranges]
    out["seconds"] = time.perf_counter() - start
    out["tiles"] = len(tiles)
    out["tile_size"] = _ccma._workspace_tile_side(model, ranges, resolution, samples, seed, wave_size, tile_size)
    if store is not None:
        out["tiles_from_store"] = counts["stored"]
    return out


def _result(model, m, threads, samples, out):
    """The map as a ccma.WorkspaceResult: `ccma workspace`'s JSON and CSV."""
    document = {"model": model.name, "samples": int(len(m["reachable"])),
                "reachable": int(_np.count_nonzero(m["reachable"])), "seconds": float(m["seconds"]),
                "threads": int(threads), "tiles": int(m["tiles"]), "tile_size": int(m["tile_size"]),
                "mode": "random" if samples > 0 else "grid", "components": list(m["components"])}
    if "tiles_from_store" in m:
        document["tiles_from_store"] = int(m["tiles_from_store"])
    table = _ccma._workspace_table(model, m)  # the CSV's columns (documents/workspace_table.h)
    details = Table({"converged": m["converged"], "assembled": m["assembled"], "steps": m["steps"],
                     "tile": m["tile"], "warning": m["warning"]})
    if out is not None:
        document["out"] = os.fspath(out)
        table.to_csv(document["out"])
    return WorkspaceResult(document, {"workspace": table, "details": details})


def workspace(model, ranges, resolution=11, samples=0, seed=1, threads=1, wave_size=64,
              client=None, chunk_size=1, tile_size=0, progress=None, max_in_flight=None, store=None, out=None,
              max_minutes=10, **control):
    """`ccma workspace`: the reachability map over `ranges` ({"z": (lo, hi), ...}; names x y z
    roll pitch yaw, metres and radians, the model's controlled components; the flags --x ...):
    a grid of `resolution` points per range, or `samples` seeded uniform draws.

    Returns a ccma.WorkspaceResult: the command's JSON as attributes (to_dict()): samples,
    reachable (the count), seconds, threads, tiles, tile_size, mode, components, and
    tiles_from_store with a store, out with out=; its CSV, one row per sample, as `table`
    (to_columns(), to_records(), to_dataframe()): the controlled components by name,
    reachable (bool), residual_energy [m^2], sigma_min (0 when unreachable), error [m or rad],
    rcond, max_limit_violation, limited_by, wave, start, ee_std_m [m] (0 when unreachable),
    stiffness_min_N_per_m [N/m] (a compliant model only: 1 / statics' most_compliant; 0 when
    unreachable or not held, NaN when every translation is rigid), u0, u1, ... (NaN when unreachable: the CSV leaves them empty). `details` holds, per
    sample, converged, assembled, steps, tile and warning. out=PATH writes the CSV there.

    `model`: a path (str or os.PathLike) or a ccma.Model; with a Dask `client`
    (distributed.Client) or a `store` it must be a path (its text is sent to the workers
    and names the map in the store).
    `tile_size`: cells per range of a tile (0: 16 for one or two ranges, fewer for more);
    part of the map's definition. `threads`: local worker threads (ignored with a client).
    `chunk_size`: tiles per task on a client; `max_in_flight`: tasks in flight at once
    (default four times the workers' threads, at least 4).
    `store`: a directory (Zarr, Debian's python3-zarr) where every finished tile is
    written as it completes; a call with the same arguments and store resumes: tiles
    already there are read back, not computed; a damaged or half-written tile is
    computed again; a store of another map is refused (ValueError).
    `progress`: True draws a bar with samples/s (tqdm, terminal or Jupyter), or a
    callable progress(done_samples, total) is called as samples finish.
    `max_minutes`: the bound on the map's estimated time, (0, 10080] [min], as --max_minutes: the
    samples are timed as they finish (the computed columns once at home); a map estimated over 5 s
    says how long on sys.stderr, then a progress line every 10 s; one estimated over max_minutes
    raises ccma.WorkBoundError a couple of seconds in (naming the estimate and the max_minutes
    that would allow it; with a store, the tiles finished are kept).
    `control`: ControlOptions fields (max_step_m, lambda_, ...). The results do not
    depend on threads, client, chunk_size, max_in_flight, store or interruptions.
    """
    out = out_path(out)
    m, model = _map(model, ranges, resolution, samples, seed, threads, wave_size, client, chunk_size, tile_size,
                    progress, max_in_flight, store, control, max_minutes)
    return _result(model, m, threads, int(samples), out)


def _map(model, ranges, resolution, samples, seed, threads, wave_size, client, chunk_size, tile_size, progress,
         max_in_flight, store, control, max_minutes):
    """The map's per-sample arrays (a dict) and the loaded model."""
    path = None
    if isinstance(model, (str, os.PathLike)):
        path = os.fspath(model)
        model = _ccma.load_model(path)
    elif client is not None or store is not None:
        raise TypeError("workspace: with a client or a store, pass the model file's path (its text is sent to "
                        "the workers and names the map)")
    range_list = [(str(name), float(lo), float(hi)) for name, (lo, hi) in dict(ranges).items()]
    options = _ccma.ControlOptions(**control)
    for name, value in (("resolution", resolution), ("samples", samples), ("seed", seed),
                        ("threads", threads), ("wave_size", wave_size), ("chunk_size", chunk_size),
                        ("tile_size", tile_size), ("max_in_flight", 1 if max_in_flight is None else max_in_flight)):
        if isinstance(value, bool) or int(value) != value:
            raise ValueError(f"workspace: {name} must be an integer, got {value!r}")
    if not 1 <= int(chunk_size) <= 100000:
        raise ValueError(f"workspace: chunk_size must lie in [1, 100000], got {chunk_size}")
    if max_in_flight is not None and not 1 <= int(max_in_flight) <= 100000:
        raise ValueError(f"workspace: max_in_flight must lie in [1, 100000], got {max_in_flight}")
    if not 1 <= int(threads) <= 1024:
        raise ValueError(f"workspace: threads must lie in [1, 1024], got {threads}")
    if int(seed) < 0:
        raise ValueError(f"workspace: seed must be >= 0, got {seed}")
    if progress is not None and progress is not True and progress is not False and not callable(progress):
        raise TypeError("workspace: progress must be True, False, None or callable as progress(done, total)")
    args = (range_list, int(resolution), int(samples), int(seed), int(wave_size), int(tile_size))
    # The most samples the options can give (the C++ side refuses more): what the estimate counts.
    total = int(samples) if int(samples) > 0 else min(int(resolution), 10 ** 6) ** len(range_list)
    estimate = _ccma._WorkEstimate("workspace", "samples", min(total, 2 ** 62), float(max_minutes))
    report = _Progress(progress)
    try:
        if client is None and store is None:
            return _ccma._workspace_compute(model, range_list, int(resolution), int(samples), int(seed),
                                            int(threads), int(wave_size), options, int(tile_size),
                                            report if progress else None, estimate), model
        with open(path, encoding="utf-8") as f:
            text = f.read()
        if client is None:
            runner, window = _LocalRunner(int(threads), text, args, control), 2 * int(threads)
        else:
            runner = _DaskRunner(client, text, args, control)
            window = max(4, 4 * sum(client.nthreads().values()))
        window = int(max_in_flight) if max_in_flight is not None else window
        return _by_tiles(runner, model, text, args, control, int(chunk_size), window, store, report,
                         estimate), model
    finally:
        report.close()
