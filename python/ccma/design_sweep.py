"""A sweep over candidate designs (docs/design.md), locally or on Dask workers.

    r = ccma.design_sweep("models/4dof_reduced.yaml",
                          {"joint1.z": [0.35, 0.5, 0.6], "joint4.z": [0.35, 0.5, 0.6]},
                          targets, client=Client(...))

Each candidate (one value per named parameter, the cartesian product of the
grid in the order given, the last name fastest) is evaluated by
ccma.evaluate_design: every target solved from home on the changed model.
With a client the model text is scattered to every worker once and loaded
there once per worker process (the cache of ccma.workspace), and candidates
are submitted in chunks, at most `max_in_flight` at a time (a lost worker's
chunks are run again by Dask); every candidate is solved from the same start
either way, so the results equal the local run exactly. With `store=` (a Zarr
directory, python/ccma/map_store.py) every finished chunk is written there as
it completes, and the same call again resumes from it.
"""
import itertools
import os

import numpy as _np

from . import _ccma
from ._tables import Table
from .results import DesignSweepResult
from .workspace import _model_on_worker


def _split(names):
    """Parameter names -> (vary, vary_length) for ccma.evaluate_design."""
    vary = [n for n in names if ":" not in n]
    vary_length = [n for n in names if ":" in n]
    return vary, vary_length


def _evaluate_candidates(text, names, targets, candidates, target_tolerance):
    """Runs on a worker (or locally): one chunk of candidates."""
    model = _model_on_worker(text)
    vary, vary_length = _split(names)
    # evaluate_design takes the values in its own order: coordinates first.
    order = [names.index(n) for n in vary + vary_length]
    out = []
    for values in candidates:
        results = _ccma.evaluate_design(model, targets, _np.asarray(values)[order], vary, vary_length,
                                        target_tolerance)
        for r in results:
            r.pop("controls")
        out.append(results)
    return out


_FIELDS = ("reached", "error", "min_singular_value", "within_limits")


def _as_arrays(part):
    """One chunk's results (per candidate, per target) as candidates x targets arrays."""
    return {k: _np.array([[r[k] for r in results] for results in part]) for k in _FIELDS}


# Bounds checked before the grid is expanded (ccma/limits.h; `ccma design --targets`).
_MAX_CANDIDATES = 1000000
_MAX_TARGETS = 1000
_MAX_MAGNITUDE = 1e4


def _check_grid(names, grids):
    """ValueError unless the grid has at most _MAX_CANDIDATES candidates (counted
    before itertools.product builds them) of finite values within 1e4 m."""
    count = 1
    for g in grids:
        count *= len(g)
    if count > _MAX_CANDIDATES:
        raise ValueError(f"design_sweep: the grid has {count} candidates; at most {_MAX_CANDIDATES} are allowed")
    for name, g in zip(names, grids):
        for v in g:
            if isinstance(v, bool) or not isinstance(v, (int, float, _np.integer, _np.floating)) or \
                    not abs(float(v)) <= _MAX_MAGNITUDE:
                raise ValueError(f"design_sweep: parameter_grid[{str(name)[:64]!r}]: {str(v)[:40]!r} is not a "
                                 "finite number within [-1e4, 1e4] (m)")


def _read_back(store, i, rows, columns):
    """Chunk i from the store, or None; ValueError when its arrays (which passed
    their sha256, so were written so on purpose) are not candidates x targets."""
    part = store.read(i)
    if part is None:
        return None
    shapes = {_np.shape(part.get(k)) for k in _FIELDS}
    if shapes != {(rows, columns)}:
        raise ValueError(f"store {store.path!r}: chunk {i} does not hold {rows} candidates x {columns} targets in "
                         f"{', '.join(_FIELDS)}; ccma writes no such chunk")
    return part


def _run_chunks(chunks, evaluate, client, text, window, store, progress, columns):
    """Every chunk's arrays, in order: read back from `store` or computed (locally, or
    on `client` with at most `window` chunks in flight), each written to the store and
    reported to progress(done_candidates, total) as it completes."""
    parts, total, done = [None] * len(chunks), sum(len(c) for c in chunks), 0
    for i in (store.done() if store is not None else ()):
        parts[i] = _read_back(store, i, len(chunks[i]), columns)
    todo = [i for i, p in enumerate(parts) if p is None]

    def finished(i, arrays):
        nonlocal done
        parts[i] = arrays
        if store is not None:
            store.write(i, arrays)
        done += len(chunks[i])
        if progress is not None:
            progress(done, total)

    done = sum(len(chunks[i]) for i, p in enumerate(parts) if p is not None)
    if client is None:
        for i in todo:
            finished(i, _as_arrays(evaluate(text, chunks[i])))
        return parts
    from ._dask_tasks import DaskTasks
    tasks, pending, queue = DaskTasks(client, text), {}, list(reversed(todo))

    def submit():
        while queue and len(pending) < window:
            i = queue.pop()
            pending[tasks.submit(evaluate, chunks[i])] = i

    submit()
    while pending:
        token, result = tasks.next_done()
        finished(pending.pop(token), _as_arrays(result))
        submit()
    return parts


def design_sweep(model, parameter_grid, targets, client=None, chunk_size=8, target_tolerance=1e-6,
                 min_singular_value=0.02, store=None, progress=None, max_in_flight=None):
    """Evaluates every candidate design of `parameter_grid` ({name: [values in m]}, names as in
    ccma.design: 'JOINT.z', 'ANCHOR:JOINT') on `targets` (N x 6).

    `model`: a path (str or os.PathLike) to the model file (its text is what the workers load).
    Returns a ccma.DesignSweepResult: `table`, one row per candidate in grid order, with one
    column per parameter (its value [m]), `all_reached`, `min_singular_value` (smallest over
    the targets, 0 when one is unreachable) and `feasible` (all reached with
    min_singular_value >= the threshold); `reached` (candidates x targets, bool);
    to_columns(), to_records(), to_dataframe().
    `store`: a Zarr directory keeping every finished chunk; the same call again resumes from
    it (a store of another sweep raises ValueError). `progress`: called as
    progress(done_candidates, total). `max_in_flight`: chunks in flight on a client (default
    four per worker thread).
    """
    if not isinstance(model, (str, os.PathLike)):
        raise TypeError("design_sweep: pass the model file's path (its text is sent to the workers)")
    _ccma.load_model(os.fspath(model))  # a regular file within the model bound, valid, before reading its text
    with open(model, "r", encoding="utf-8") as f:
        text = f.read()
    if not parameter_grid:
        raise ValueError("design_sweep: parameter_grid names no parameter")
    names = list(parameter_grid)
    grids = [list(parameter_grid[n]) for n in names]
    if any(len(g) == 0 for g in grids):
        raise ValueError("design_sweep: every parameter needs at least one value")
    _check_grid(names, grids)
    candidates = [list(c) for c in itertools.product(*grids)]
    targets = _np.atleast_2d(_np.asarray(targets, dtype=float))
    if targets.ndim != 2 or targets.shape[1] != 6:
        raise ValueError("design_sweep: targets must be N x 6 (x, y, z, roll, pitch, yaw)")
    if not 1 <= len(targets) <= _MAX_TARGETS or not _np.all(_np.abs(targets) <= _MAX_MAGNITUDE):
        raise ValueError(f"design_sweep: targets must be 1 to {_MAX_TARGETS} rows of finite numbers within "
                         f"[-1e4, 1e4], got {len(targets)} rows")
    if not isinstance(chunk_size, int) or not 1 <= chunk_size <= 10000:
        raise ValueError("design_sweep: chunk_size must be an integer in [1, 10000]")
    chunks = [candidates[i:i + chunk_size] for i in range(0, len(candidates), chunk_size)]
    if progress is not None and not callable(progress):
        raise TypeError("design_sweep: progress must be callable as progress(done, total)")
    if max_in_flight is not None and (not isinstance(max_in_flight, int) or not 1 <= max_in_flight <= 100000):
        raise ValueError("design_sweep: max_in_flight must be an integer in [1, 100000]")
    kept = None
    if store is not None:
        from .map_store import MapStore
        key = {"batch": "ccma.design_sweep", "model": text, "names": names, "grid": grids,
               "targets": targets.tolist(), "chunk_size": chunk_size, "target_tolerance": target_tolerance}
        kept = MapStore(store, key, len(chunks))
    window = max_in_flight or (max(4, 4 * sum(client.nthreads().values())) if client is not None else 1)

    def evaluate(text_or_future, chunk):
        return _evaluate_candidates(text_or_future, names, targets, chunk, target_tolerance)

    parts = _run_chunks(chunks, evaluate, client, text, window, kept, progress, len(targets))
    reached = _np.concatenate([_np.asarray(p["reached"], dtype=bool) for p in parts])
    sigma = _np.concatenate([_np.asarray(p["min_singular_value"], dtype=float) for p in parts])
    sigma = _np.where(reached, sigma, 0.0).min(axis=1)
    columns = {name: [float(c[k]) for c in candidates] for k, name in enumerate(names)}
    columns["all_reached"] = reached.all(axis=1)
    columns["min_singular_value"] = sigma
    columns["feasible"] = reached.all(axis=1) & (sigma >= min_singular_value)
    reached.flags.writeable = False
    return DesignSweepResult(names, Table(columns), reached)
