"""Start-up hook of the build tree's Python folder (build/python/sitecustomize.py).

Python imports the first `sitecustomize` on sys.path once at start-up, so with
PYTHONPATH=build/python it runs this file before the first line of a script.
The ccma extension uses NumPy, built for Debian's python3 (python3-numpy). An
interpreter of the same Python version that has no NumPy of its own (pyenv's,
a virtual environment without system packages) would fail on `import numpy`
written before `import ccma` (ccma/__init__.py only helps once it runs). So,
in that case only, Debian's package folder is appended to sys.path, after the
interpreter's own folders, which keep precedence. Then the `sitecustomize`
this file hides (Debian's, for instance) runs as it would have.

It costs a few file look-ups at start-up and imports nothing that Python has
not loaded already (no importlib.util), whatever the script imports later.
"""
import importlib.machinery as _machinery
import os as _os
import sys as _sys

_DEBIAN_PACKAGES = "/usr/lib/python3/dist-packages"
_HERE = _os.path.dirname(_os.path.realpath(__file__))


def _extension_fits_this_python():
    """Whether ccma/_ccma next to this file was built for this interpreter's version."""
    package = _os.path.join(_HERE, "ccma")
    return any(_os.path.exists(_os.path.join(package, "_ccma" + suffix))
               for suffix in _machinery.EXTENSION_SUFFIXES)


def _add_debian_numpy():
    if _DEBIAN_PACKAGES in _sys.path or not _extension_fits_this_python():
        return
    if not _os.path.isdir(_os.path.join(_DEBIAN_PACKAGES, "numpy")):
        return
    if not _findable("numpy"):
        _sys.path.append(_DEBIAN_PACKAGES)


def _findable(name):
    """Whether `import name` would find a top-level module (without importing it)."""
    for finder in _sys.meta_path:
        find_spec = getattr(finder, "find_spec", None)
        if find_spec is not None and find_spec(name, None) is not None:
            return True
    return False


def _is_here(entry):
    return _os.path.realpath(entry or _os.curdir) == _HERE


def _run_hidden_sitecustomize():
    """Runs the next `sitecustomize` on sys.path after this folder, if any."""
    entries = list(_sys.path)
    later = next((entries[i + 1:] for i, e in enumerate(entries) if _is_here(e)), entries)
    spec = _machinery.PathFinder.find_spec("sitecustomize", [e for e in later if not _is_here(e)])
    if spec is None or spec.loader is None:
        return
    module = type(_sys)(spec.name)  # a new module object, as importlib.util.module_from_spec makes
    module.__spec__, module.__loader__, module.__file__ = spec, spec.loader, spec.origin
    spec.loader.exec_module(module)


_add_debian_numpy()
_run_hidden_sitecustomize()
