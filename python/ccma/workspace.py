"""Workspace maps from Python, on this machine or on a Dask cluster.

    import ccma
    m = ccma.workspace("models/4dof_reduced.yaml", {"z": (0.4, 1.0), "x": (-0.5, 0.5)},
                       resolution=25, threads=2)
    m["reachable"]  # NumPy bool per sample; m["poses"] n x 6, m["controls"], m["sigma_min"], ...

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
    first, and the finished tiles' results that a tile not yet sent needs."""

    def __init__(self, tiles):
        self.tiles = tiles
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
        """Up to `count` ready tiles and, for each, the results of the tiles it depends on."""
        group, inputs = [], []
        while self.ready and len(group) < count:
            _, t = heapq.heappop(self.ready)
            group.append(t)
            inputs.append([self.results[d] for d in self.tiles[t]["depends_on"]])
            for d in self.tiles[t]["depends_on"]:
                self.unsent_users[d] -= 1
                if self.unsent_users[d] == 0:
                    del self.results[d]
        return group, inputs

    def finish(self, t, result):
        if self.unsent_users[t] > 0:
            self.results[t] = result
        for u in self.users[t]:
            self.waiting[u] -= 1
            if self.waiting[u] == 0:
                heapq.heappush(self.ready, (self.tiles[u]["order"], u))


def _on_cluster(client, path, model, args, control, chunk, window, progress):
    """The map on a Dask client: tiles as tasks, sent when the tiles they depend
    on are finished, at most `window` in flight, placed in map order."""
    start = time.perf_counter()
    ranges, resolution, samples, seed, wave_size, tile_size = args
    from distributed import as_completed
    with open(path, encoding="utf-8") as f:
        text = f.read()
    # hash=False: a fresh key per call (a hashed key shared with an earlier
    # call would be released, and its tasks cancelled, when that call's
    # future is dropped).
    text_future = client.scatter(text, broadcast=True, hash=False)
    tiles = _ccma._workspace_tiles(model, ranges, resolution, samples, seed, wave_size, tile_size)
    n = sum(len(t["rows"]) for t in tiles)
    schedule = _Schedule(tiles)
    group_of, out, done = {}, {}, 0
    running = as_completed()

    def submit_ready():
        while len(group_of) < window and schedule.ready:
            group, inputs = schedule.take(chunk)
            # Tiles nearer home first: more tiles wait for them.
            future = client.submit(_evaluate_tiles, text_future, args, dict(control), group, inputs, pure=False,
                                   priority=-tiles[group[0]]["order"])
            group_of[future.key] = group
            running.add(future)

    submit_ready()
    for future in running:
        for t, blob in zip(group_of.pop(future.key), future.result()):
            _place(out, tiles[t]["rows"], pickle.loads(blob), n)
            schedule.finish(t, blob)
            done += len(tiles[t]["rows"])
        if progress is not None:
            progress(done, n)
        submit_ready()
    out["components"] = [r[0] for r in ranges]
    out["seconds"] = time.perf_counter() - start
    out["tiles"] = len(tiles)
    return out


def workspace(model, ranges, resolution=11, samples=0, seed=1, threads=1, wave_size=64,
              client=None, chunk_size=1, tile_size=0, progress=None, max_in_flight=None, **control):
    """Reachability map over `ranges` ({"z": (lo, hi), ...}; names x y z roll pitch yaw,
    metres and radians, the model's controlled components): a grid of `resolution` points
    per range, or `samples` seeded uniform draws. Returns a dict of NumPy arrays, one entry
    per sample: poses (n x 6), reachable, converged, assembled, controls (n x controls),
    residual_energy [m^2], error [m or rad], sigma_min, rcond, max_limit_violation, wave,
    start, steps, tile; lists limited_by and warning; and components, seconds, tiles.

    `model`: a path (str or os.PathLike) or a ccma.Model; with a Dask `client`
    (distributed.Client) it must be a path, whose text is sent to each worker once.
    `tile_size`: cells per range of a tile (0: 16 for one or two ranges, fewer for more);
    part of the map's definition. `threads`: local worker threads (ignored with a client).
    `chunk_size`: tiles per task on a client; `max_in_flight`: tasks in flight at once
    (default four times the workers' threads, at least 4).
    `progress`: called as progress(done_samples, total) as samples finish.
    `control`: ControlOptions fields (max_step_m, lambda_, ...). The results do not
    depend on threads, client, chunk_size or max_in_flight.
    """
    path = None
    if isinstance(model, (str, os.PathLike)):
        path = os.fspath(model)
        model = _ccma.load_model(path)
    elif client is not None:
        raise TypeError("workspace: with a client, pass the model file's path (its text is sent to the workers)")
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
    if int(seed) < 0:
        raise ValueError(f"workspace: seed must be >= 0, got {seed}")
    if progress is not None and not callable(progress):
        raise TypeError("workspace: progress must be callable as progress(done, total)")
    args = (range_list, int(resolution), int(samples), int(seed), int(wave_size), int(tile_size))
    if client is None:
        return _ccma._workspace_compute(model, range_list, int(resolution), int(samples), int(seed),
                                        int(threads), int(wave_size), options, int(tile_size), progress)
    window = int(max_in_flight) if max_in_flight is not None else max(4, 4 * sum(client.nthreads().values()))
    return _on_cluster(client, path, model, args, control, int(chunk_size), window, progress)
