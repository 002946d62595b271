"""A sweep over candidate designs (docs/design.md), locally or on Dask workers.

    r = ccma.design_sweep("models/4dof_reduced.yaml",
                          {"joint1.z": [0.35, 0.5, 0.6], "joint4.z": [0.35, 0.5, 0.6]},
                          targets, client=Client(...))

Each candidate (one value per named parameter, the cartesian product of the
grid in the order given, the last name fastest) is evaluated by
ccma.evaluate_design: every target solved from home on the changed model.
With a client the model text is scattered to every worker once and loaded
there once per worker process (the cache of ccma.workspace), and candidates
are submitted in chunks; every candidate is solved from the same start either
way, so the results equal the local run exactly.
"""
import itertools
import os

import numpy as _np

from . import _ccma
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


def design_sweep(model, parameter_grid, targets, client=None, chunk_size=8, target_tolerance=1e-6,
                 min_singular_value=0.02):
    """Evaluates every candidate design of `parameter_grid` ({name: [values in m]}, names as in
    ccma.design: 'JOINT.z', 'ANCHOR:JOINT') on `targets` (N x 6).

    `model`: a path (str or os.PathLike) to the model file (its text is what the workers load).
    Returns a list, one dict per candidate in grid order: `values` ({name: value}), `reached`
    (one boolean per target), `all_reached`, `min_singular_value` (smallest over the targets, 0
    when one is unreachable), `feasible` (all reached with min_singular_value >= the threshold).
    """
    if not isinstance(model, (str, os.PathLike)):
        raise TypeError("design_sweep: pass the model file's path (its text is sent to the workers)")
    with open(model, "r", encoding="utf-8") as f:
        text = f.read()
    if not parameter_grid:
        raise ValueError("design_sweep: parameter_grid names no parameter")
    names = list(parameter_grid)
    grids = [list(parameter_grid[n]) for n in names]
    if any(len(g) == 0 for g in grids):
        raise ValueError("design_sweep: every parameter needs at least one value")
    candidates = [list(c) for c in itertools.product(*grids)]
    targets = _np.atleast_2d(_np.asarray(targets, dtype=float))
    if targets.shape[1] != 6:
        raise ValueError("design_sweep: targets must be N x 6 (x, y, z, roll, pitch, yaw)")
    if not isinstance(chunk_size, int) or not 1 <= chunk_size <= 10000:
        raise ValueError("design_sweep: chunk_size must be an integer in [1, 10000]")
    chunks = [candidates[i:i + chunk_size] for i in range(0, len(candidates), chunk_size)]
    if client is None:
        parts = [_evaluate_candidates(text, names, targets, c, target_tolerance) for c in chunks]
    else:
        # hash=False, as in ccma.workspace: a fresh key per call. A key hashed
        # from the text would be shared with an earlier call on this client, and
        # releasing that call's future would cancel this call's tasks.
        text_future = client.scatter(text, broadcast=True, hash=False)
        futures = [client.submit(_evaluate_candidates, text_future, names, targets, c, target_tolerance,
                                 pure=False) for c in chunks]
        parts = client.gather(futures)
    out = []
    for values, results in zip(candidates, [r for part in parts for r in part]):
        reached = [bool(r["reached"]) for r in results]
        sigma = min(r["min_singular_value"] if r["reached"] else 0.0 for r in results)
        out.append({"values": dict(zip(names, values)), "reached": reached, "all_reached": all(reached),
                    "min_singular_value": sigma,
                    "feasible": all(reached) and sigma >= min_singular_value})
    return out
