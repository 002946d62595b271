"""ccma.replay: `ccma replay` from Python (docs/replay.md)."""
import math as _math

import numpy as _np

from . import _ccma
from ._tables import Table
from .results import ReplayResult

_COMPONENTS = ("x", "y", "z", "roll", "pitch", "yaw")
_UNITS = ("m", "m", "m", "rad", "rad", "rad")


def _wrap(angles):
    """WrapAngle (ccma/rotation.h): the IEEE remainder by 2 pi, in (-pi, pi]."""
    out = _np.array([_math.remainder(a, 2 * _math.pi) for a in angles], dtype=float)
    out[out <= -_math.pi] += 2 * _math.pi
    return out


def _end_effector_table(a):
    """end_effector.csv of `ccma replay` (apps/replay_report.cc WriteReplayCsv)."""
    columns = {"time_s": a["time"]}
    for c, (name, unit) in enumerate(zip(_COMPONENTS, _UNITS)):
        columns["cmd_%s_%s" % (name, unit)] = a["commanded"][:, c]
    for c, (name, unit) in enumerate(zip(_COMPONENTS, _UNITS)):
        columns["%s_%s" % (name, unit)] = a["tracked"][:, c]
    difference = a["tracked"] - a["commanded"]
    for c, name in enumerate(_COMPONENTS):
        columns["err_%s_%s" % (name, "rad" if c >= 3 else "mm")] = \
            _wrap(difference[:, c]) if c >= 3 else 1000 * difference[:, c]
    columns["residual_energy_m2"] = a["residual_energy"]
    columns["torn"] = a["torn"]
    return Table(columns)


def _bases_table(model, a):
    """bases.csv of `ccma replay`: set and true pose of every base, the actuated joints."""
    columns = {"time_s": a["time"]}
    for k in range(model.num_bases):
        first = model.base_control(k)
        names = model.mobile_bases[k].control_names  # a legged base's height, roll, pitch too
        for c, name in enumerate(names):
            columns["set%d_%s" % (k, name)] = a["set_controls"][:, first + c]
        for c, name in enumerate(names):
            columns["base%d_%s" % (k, name)] = a["true_controls"][:, first + c]
    for joint in model.joints:
        if joint.actuated:
            unit = "rad" if joint.type == "revolute" else "m"
            columns["u_%s_%s" % (joint.name, unit)] = a["true_controls"][:, joint.control]
    columns["torn"] = a["torn"]
    return Table(columns)


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
    document, arrays = _ccma._replay(model, waypoints, _ccma.ReplayOptions() if options is None else options)
    tables = {"end_effector": _end_effector_table(arrays), "bases": _bases_table(model, arrays)}
    return ReplayResult(document, tables)
