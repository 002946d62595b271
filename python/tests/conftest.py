"""Shared fixtures: the bundled models, the `ccma` tool (the C++ reference the
Python results are compared with) and a helper to run it."""
import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
MODELS = sorted((ROOT / "models").glob("*.yaml"))


def tool_path():
    return os.environ.get("CCMA_TOOL", str(ROOT / "build" / "apps" / "ccma"))


def run_tool(*args, expect=0):
    """Runs `ccma ARGS` (an argument list, no shell); returns its JSON."""
    p = subprocess.run([tool_path(), *args], capture_output=True, text=True, timeout=600)
    assert p.returncode == expect, p.stderr
    return json.loads(p.stdout) if expect == 0 else p


def csv_numbers(values):
    # repr() of a float reads back to the same double in C++ (strtod).
    return ",".join(repr(float(v)) for v in values)


@pytest.fixture(params=MODELS, ids=[m.stem for m in MODELS])
def model_path(request):
    return str(request.param)


# A hostile store (issue 34): an array that runs code when zarr decodes it.
class _Touch:
    """Unpickling this creates `marker`: what a pickled payload could run."""

    def __init__(self, marker):
        self.marker = marker

    def __reduce__(self):
        return pathlib.Path.touch, (pathlib.Path(self.marker),)


def plant_pickled_array(store_path, index, field, marker):
    """Replaces chunk `index`'s array `field` by an object array whose pickle
    filter (zarr's object_codec) would run _Touch on decoding."""
    import numcodecs
    import numpy as np
    import zarr
    group = zarr.open_group(str(store_path / "chunks" / str(index)), mode="a")
    del group[field]
    payload = np.empty(5, dtype=object)
    payload[:] = [_Touch(marker)] * 5
    group.array(field, payload, dtype=object, object_codec=numcodecs.Pickle(), chunks=(5,))
    meta = json.loads((store_path / "chunks" / str(index) / field / ".zarray").read_text())
    assert meta["dtype"] == "|O" and meta["filters"] == [{"id": "pickle", "protocol": 5}]
