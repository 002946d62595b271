"""ccma.replay: `ccma replay` from Python (docs/replay.md)."""
from . import _ccma
from .results import ReplayResult


def replay(model, waypoints, options=None):
    """`ccma replay`: the paper's closed loop, simulated: the bases track the control
    solution with noise and latency, the chain follows (execution/replay.h).

    model: a ccma.Model; waypoints: a list of ccma.Waypoint or an (N x 7) array of rows
    [time, x, y, z, roll, pitch, yaw]; options: a ccma.ReplayOptions (default noise,
    seed 1, as the command).

    Returns a ccma.ReplayResult: the command's JSON as attributes (to_dict(); without
    `files` and `plots`, as nothing is written): converged, torn, torn_samples,
    trustworthy, rmse (x_mm ... [mm], yaw_rad ... [rad]), noise, controller, warning, ...;
    the command's two CSV files as tables: `tables['end_effector']` (also `table`) and
    `tables['bases']`. Raises ValueError on waypoints or options out of range (naming the
    waypoint)."""
    document, tables = _ccma._replay(model, waypoints, _ccma.ReplayOptions() if options is None else options)
    return ReplayResult(document, tables)
