"""ccma.design: `ccma design` from Python (docs/design.md)."""
import os as _os
import warnings as _warnings

import numpy as _np

from . import _ccma
from ._tables import out_path
from .results import DesignResult
from .viewer import _write_replacing


def _targets(targets):
    """N x 6 rows x, y, z [m], roll, pitch, yaw [rad]; a waypoint CSV path (as --targets; times ignored)."""
    if isinstance(targets, (str, _os.PathLike)):
        return _np.array([[*w.position, *w.rpy] for w in _ccma.load_waypoints(_os.fspath(targets))], dtype=float)
    return _np.atleast_2d(_np.asarray(targets, dtype=float))


def design(model, targets, vary=(), vary_length=(), max_change=0.5, min_length=0.02, min_singular_value=0.02,
           target_tolerance=1e-6, design_iterations=30, objective="reach", mocap_noise_m=0.001,
           mocap_noise_rad=0.003, out=None, max_minutes=10):
    """`ccma design`: moves the named geometry until every target is reachable with margin.

    model: the model file's path (as --model) or a ccma.Model. targets: N x 6 rows x, y, z [m],
    roll, pitch, yaw [rad], or a waypoint CSV's path (as --targets; times ignored). vary:
    'JOINT.x|y|z|point' items, vary_length: 'ANCHOR:JOINT' items. Keywords as the flags:
    max_change [m], min_length [m], min_singular_value [m or rad per control unit],
    target_tolerance [m or rad], design_iterations, objective ('reach', 'payload', 'peak_push',
    'ee_std', 'stiffness', 'deflection'), mocap_noise_m [m], mocap_noise_rad [rad]. out: write the designed model file there.
    max_minutes: the bound on the design's estimated time, (0, 10080] [min], as --max_minutes: the
    iterations are timed as they go (the objective's on their own); a design estimated over 5 s
    says how long on sys.stderr, then a progress line every 10 s; one estimated over max_minutes
    raises ccma.WorkBoundError (naming the estimate and the max_minutes that would allow it).

    Returns a ccma.DesignResult: the command's JSON as attributes (to_dict()): converged,
    reached, reached_before, targets, iterations, changed, changed_points, objective, warning;
    `new_model` is the designed Model. Given a path, it does what the command does: the new
    numbers are patched into the file's text (12 significant digits), the text loaded back and
    the targets checked in that model, so the result equals the command's; given a Model, they
    are checked in the designed Model itself (no text to patch; out= is then refused).
    Raises ValueError on bad names or values (ccma.ModelError for a bad model file).
    """
    out = out_path(out)
    text, source = None, "<design>"
    if isinstance(model, (str, _os.PathLike)):
        source = _os.fspath(model)
        _ccma.load_model(source)  # a regular file within the model bound, valid (its warnings shown once)
        with open(source, "r", encoding="utf-8") as f:
            text = f.read()
        with _warnings.catch_warnings():
            _warnings.simplefilter("ignore")
            model = _ccma.load_model_from_string(text, source)
    elif out is not None:
        raise ValueError("design: out= needs the model file's path (its text is what is patched and written)")
    if out is not None:
        source = _os.fspath(out)
    document, new_model, new_text = _ccma._design(
        model, text, source, _targets(targets), list(vary), list(vary_length), float(max_change), float(min_length),
        float(min_singular_value), float(target_tolerance), int(design_iterations), str(objective),
        float(mocap_noise_m), float(mocap_noise_rad), float(max_minutes))
    if out is not None:
        _write_replacing(source, new_text.encode("utf-8"))
        document["out"] = source
    return DesignResult(document, new_model=new_model)
