"""ccma: simulation and kinematic control of closed-loop mechanisms driven by
mobile robots (Constrained Collaborative Mobile Agents, after Kumar and Coros).

    import ccma
    model = ccma.load_model("models/4dof_reduced.yaml")
    result = ccma.ForwardProblem(model).assemble(model.home_controls)
    print(result.assembled, result.end_effector.position)
    control = ccma.ControlProblem(model)
    print(control.move_to([0, 0.05, 0.6, 0, 0, 0]).converged)

Every analysis returns a result whose attributes are the keys of the JSON the
`ccma` command prints for it, and whose to_dict() is that JSON; one that the
command writes as CSV carries it as a ccma.Table (to_columns(), to_dataframe()).
Names are the tool's: a flag that is a Python keyword takes a trailing
underscore (--lambda: lambda_, --from: from_).
Units: metres, radians, seconds, E in m^2. Arrays are NumPy float64.
Reference: docs/python.md; type hints: ccma/_ccma.pyi, ccma/results.py.
"""
import sys as _sys

try:
    import numpy as _numpy  # noqa: F401  (the extension returns NumPy arrays)
except ImportError:  # pragma: no cover - depends on the interpreter
    # An interpreter other than Debian's (e.g. pyenv's) of the version the
    # extension was built for, without a NumPy of its own: use Debian's
    # python3-numpy, placed after the interpreter's own packages so that those
    # still win. With PYTHONPATH=build/python the build tree's sitecustomize
    # (python/sitecustomize.py) has done this already at start-up, so that
    # `import numpy` works before `import ccma` too; this covers the rest
    # (an installed copy, python -S).
    _debian = "/usr/lib/python3/dist-packages"
    if _debian not in _sys.path:
        _sys.path.append(_debian)
    import numpy as _numpy  # noqa: F401

from ._ccma import *  # noqa: F401,F403
from ._ccma import __version__  # noqa: F401
from ._records import Record  # noqa: F401
from ._tables import Table  # noqa: F401
from .results import (CheckResult, DesignResult, DesignSweepResult, DynamicsResult, ExportResult,  # noqa: F401
                      GenerateResult, ImportResult, PlanResult, ReplayResult, RetimeResult, StaticsResult,
                      TrajectoryResult, ViewResult, WorkspaceResult)
from .viewer import view  # noqa: F401
from .workspace import workspace  # noqa: F401
from .design import design  # noqa: F401
from .design_sweep import design_sweep  # noqa: F401
from .replay import replay  # noqa: F401
from .robots import export, import_robot  # noqa: F401
from .generate import generate  # noqa: F401
