"""`import numpy` before `import ccma`, and after it, in an interpreter that has
no NumPy of its own (a virtual environment without system packages stands in
for pyenv's python3 and the like), with PYTHONPATH=build/python as
docs/python.md's quick start runs it. The build tree's sitecustomize lets
that interpreter find Debian's python3-numpy, after its own folders."""
import json
import os
import pathlib
import subprocess
import sys

import pytest

import ccma
from conftest import ROOT

DEBIAN_PACKAGES = pathlib.Path("/usr/lib/python3/dist-packages")
BUILD_PYTHON = pathlib.Path(ccma.__file__).resolve().parents[1]  # build/python
MODEL = str(ROOT / "models" / "4dof_reduced.yaml")

NUMPY_FIRST = """
import numpy as np
import ccma
"""
CCMA_FIRST = """
import ccma
import numpy as np
"""
REPORT = """
import json, sys
model = ccma.load_model(sys.argv[1])
r = ccma.ForwardProblem(model).assemble(model.home_controls)
print(json.dumps({"numpy": np.__file__, "ndarray": isinstance(r.controls, np.ndarray),
                  "controls": r.controls.tolist(), "assembled": r.assembled}))
"""


@pytest.fixture(scope="module")
def bare_python(tmp_path_factory):
    """The python of a fresh virtual environment without system packages: no NumPy."""
    if not (DEBIAN_PACKAGES / "numpy").is_dir():
        pytest.skip("no Debian python3-numpy to fall back on")
    if not (BUILD_PYTHON / "sitecustomize.py").is_file():
        pytest.fail("build/python/sitecustomize.py is missing (python/CMakeLists.txt copies it)")
    env_dir = tmp_path_factory.mktemp("venv")
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(env_dir)], check=True, timeout=120)
    return str(env_dir / "bin" / "python")


def run(python, code, *args, pythonpath=None):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    if pythonpath is not None:
        env["PYTHONPATH"] = pythonpath
    return subprocess.run([python, "-c", code, *args], capture_output=True, text=True, env=env, timeout=300)


def test_the_bare_interpreter_has_no_numpy(bare_python):
    """Without the build tree on its path, `import numpy` fails: the case to cover."""
    p = run(bare_python, "import numpy")
    assert p.returncode != 0 and "No module named 'numpy'" in p.stderr


@pytest.mark.parametrize("order", [NUMPY_FIRST, CCMA_FIRST], ids=["numpy_first", "ccma_first"])
def test_both_import_orders_work(bare_python, order):
    p = run(bare_python, order + REPORT, MODEL, pythonpath=str(BUILD_PYTHON))
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    assert out["numpy"].startswith(str(DEBIAN_PACKAGES) + os.sep)
    assert out["ndarray"] and out["assembled"]
    home = ccma.load_model(MODEL).home_controls
    assert out["controls"] == home.tolist()


def test_the_interpreters_own_numpy_wins(bare_python, tmp_path):
    """An interpreter with a NumPy of its own keeps it: nothing is added to its path."""
    own = tmp_path / "own"
    (own / "numpy").mkdir(parents=True)
    (own / "numpy" / "__init__.py").write_text("")
    code = "import sys, numpy; print(numpy.__file__); print(%r in sys.path)" % str(DEBIAN_PACKAGES)
    p = run(bare_python, code, pythonpath=os.pathsep.join([str(BUILD_PYTHON), str(own)]))
    assert p.returncode == 0, p.stderr
    assert p.stdout.split() == [str(own / "numpy" / "__init__.py"), "False"]


def test_the_hidden_sitecustomize_still_runs(bare_python, tmp_path):
    """build/python/sitecustomize.py hides any later one (Debian's, say): it runs it."""
    later = tmp_path / "later"
    later.mkdir()
    (later / "sitecustomize.py").write_text("import builtins\nbuiltins.CCMA_TEST_MARK = 42\n")
    p = run(bare_python, "import builtins; print(builtins.CCMA_TEST_MARK)",
            pythonpath=os.pathsep.join([str(BUILD_PYTHON), str(later)]))
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "42"
