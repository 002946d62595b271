"""ccma.replay: `ccma replay` from Python (docs/replay.md)."""
import os as _os

from . import _ccma
from .results import ReplayResult


def replay(model, waypoints, options=None):
    """`ccma replay`: the paper's closed loop, simulated: the bases track the control
    solution with noise and latency, the chain follows (execution/replay.h).

    model: a ccma.Model or the model file's path (as --model); waypoints: a list of
    ccma.Waypoint, an (N x 7) array of rows [time, x, y, z, roll, pitch, yaw], or a
    waypoint CSV's path (as --waypoints; read by ccma.load_waypoints); options: a
    ccma.ReplayOptions (default noise, seed 1, as the command).

    Returns a ccma.ReplayResult: the command's JSON as attributes (to_dict(); without
    `files` and `plots`, as nothing is written): converged, torn, torn_samples,
    trustworthy, rmse (x_mm ... [mm], yaw_rad ... [rad]), noise, controller, warning, ...;
    the command's two CSV files as tables: `tables['end_effector']` (also `table`) and
    `tables['bases']`. Raises ValueError on waypoints or options out of range (naming the
    waypoint)."""
    if isinstance(model, (str, _os.PathLike)):
        model = _ccma.load_model(_os.fspath(model))
    if isinstance(waypoints, (str, _os.PathLike)):
        waypoints = _ccma.load_waypoints(_os.fspath(waypoints))
    document, tables = _ccma._replay(model, waypoints, _ccma.ReplayOptions() if options is None else options)
    return ReplayResult(document, tables)
