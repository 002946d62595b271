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
