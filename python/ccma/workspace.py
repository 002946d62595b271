"""Workspace maps from Python, on this machine or on a Dask cluster.

    import ccma
    m = ccma.workspace("models/4dof_reduced.yaml", {"z": (0.4, 1.0), "x": (-0.5, 0.5)},
                       resolution=25, threads=2)
    m["reachable"]  # NumPy bool per sample; m["poses"] n x 6, m["controls"], m["sigma_min"], ...

    from distributed import Client
    m = ccma.workspace(path, ranges, client=Client("tcp://scheduler:8786"))

The samples, their waves and each sample's start are decided here (C++,
analyses/workspace.h); with a client, every wave is split into chunks that
the workers solve (ccma must be importable on them). The model file's text
is scattered to every worker once and loaded there once per worker process
(cached by its hash), so a distributed map equals the local one exactly.
Reference: docs/workspace.md, docs/python.md.
"""
import hashlib
import os

import numpy as _np

from . import _ccma

_MODELS = {}  # per worker process: hash of the model text -> Model


def _model_on_worker(text):
    key = hashlib.sha256(text.encode("utf-8")).hexdigest()
    model = _MODELS.get(key)
    if model is None:
        model = _MODELS[key] = _ccma.load_model_from_string(text, "workspace model")
    return model


def _evaluate_chunk(text, ranges, control_kw, poses, states, controls):
    """Runs on a worker: one chunk of a wave, one thread."""
    model = _model_on_worker(text)
    control = _ccma.ControlOptions(**control_kw)
    return _ccma._workspace_evaluate(model, ranges, poses, states, controls, 1, control)


def _merge(parts):
    out = {}
    for key in parts[0]:
        values = [p[key] for p in parts]
        if isinstance(values[0], list):
            out[key] = [v for part in values for v in part]
        else:
            out[key] = _np.concatenate(values)
    return out


def workspace(model, ranges, resolution=11, samples=0, seed=1, threads=1, wave_size=64,
              client=None, chunk_size=16, **control):
    """Reachability map over `ranges` ({"z": (lo, hi), ...}; names x y z roll pitch yaw,
    metres and radians, the model's controlled components): a grid of `resolution` points
    per range, or `samples` seeded uniform draws. Returns a dict of NumPy arrays, one entry
    per sample: poses (n x 6), reachable, converged, assembled, controls (n x controls),
    residual_energy [m^2], error [m or rad], sigma_min, rcond, max_limit_violation, wave,
    start, steps; lists limited_by and warning; and components, seconds.

    `model`: a path (str or os.PathLike) or a ccma.Model; with a Dask `client`
    (distributed.Client) it must be a path, whose text is sent to each worker once.
    `threads`: local worker threads (ignored with a client). `control`: ControlOptions
    fields (max_step_m, lambda_, ...). The results do not depend on threads, client
    or chunk_size.
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
                        ("threads", threads), ("wave_size", wave_size), ("chunk_size", chunk_size)):
        if isinstance(value, bool) or int(value) != value:
            raise ValueError(f"workspace: {name} must be an integer, got {value!r}")
    if not 1 <= int(chunk_size) <= 100000:
        raise ValueError(f"workspace: chunk_size must lie in [1, 100000], got {chunk_size}")
    if int(seed) < 0:
        raise ValueError(f"workspace: seed must be >= 0, got {seed}")
    evaluate = None
    if client is not None:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        # hash=False: a fresh key per call (a hashed key shared with an earlier
        # call would be released, and its tasks cancelled, when that call's
        # future is dropped).
        text_future = client.scatter(text, broadcast=True, hash=False)
        chunk = int(chunk_size)

        def evaluate(poses, states, controls):
            futures = [
                client.submit(_evaluate_chunk, text_future, range_list, dict(control),
                              poses[i:i + chunk], states[i:i + chunk], controls[i:i + chunk], pure=False)
                for i in range(0, len(poses), chunk)
            ]
            return _merge(client.gather(futures))

    return _ccma._workspace_compute(model, range_list, int(resolution), int(samples), int(seed),
                                    int(threads), int(wave_size), options, evaluate)
