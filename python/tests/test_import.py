"""ccma.import_robot on the bundled example-parallel-robots copies (docs/import.md)."""
import math
import os

import numpy as np
import pytest

import ccma
from conftest import run_tool

ROBOTS = os.path.join(os.path.dirname(__file__), "..", "..", "models", "robots", "example-parallel-robots")


def test_five_bar_imports_assembled_with_source_coordinates(tmp_path):
    folder = os.path.join(ROBOTS, "5bar_linkage")
    out = tmp_path / "5bar.yaml"
    result = ccma.import_robot(os.path.join(folder, "robot.urdf"), closures=os.path.join(folder, "robot.yaml"),
                               end_effector="effector", out=str(out))
    assert out.exists() and result.out == str(out)
    model = result.new_model
    assert model.num_controls == 2 and sorted(result.actuated) == ["mot1", "mot2"]
    assert result.controlled == ["y", "z"] and result.controlled_chosen is True
    assert result.assembled and result.residual_energy < 1e-20 and result.closures == 1
    assert np.allclose(model.home_controls, [0.0, 0.0])
    problem = ccma.ForwardProblem(model)
    result = problem.solve(np.array([0.1, -0.1]))
    assert result.assembled
    assert result.residual_energy < 1e-20
    # The motors' q are their controls.
    motors = {j.name: j for j in model.joints if j.actuated}
    assert set(motors) == {"mot1", "mot2"}


@pytest.mark.parametrize("robot, end_effector, moved", [
    ("5bar_linkage", "effector", ["y", "z"]),
    ("robot_delta", "eff", ["y", "z"]),
    ("cassie_like", "foot", ["x", "y", "z", "roll", "pitch"]),
])
def test_import_controls_what_the_motors_move_as_the_cli_does(tmp_path, robot, end_effector, moved):
    """Without controlled=, import_robot controls the components the motors move at home
    (translations first), the same ones `ccma import` chooses; `ccma check` counts that
    many end-effector DOF. Components the motors cannot move are refused (ValueError),
    with the CLI's message."""
    folder = os.path.join(ROBOTS, robot)
    files = dict(closures=os.path.join(folder, "robot.yaml"), end_effector=end_effector)
    out = tmp_path / "robot.yaml"
    imported = ccma.import_robot(os.path.join(folder, "robot.urdf"), out=str(out), **files)
    assert imported.controlled == moved and imported.controlled_chosen is True
    assert imported.new_model.controlled == moved
    cli = run_tool("import", "--from=" + os.path.join(folder, "robot.urdf"), "--closures=" + files["closures"],
                   "--end_effector=" + end_effector, "--out=" + str(tmp_path / "cli.yaml"))
    assert cli["controlled"] == moved and cli["controlled_chosen"] is True
    assert run_tool("check", "--model=" + str(out))["end_effector_dof"] == len(moved)
    given = ccma.import_robot(os.path.join(folder, "robot.urdf"), controlled=moved[::-1], **files)
    assert given.controlled == moved and given.controlled_chosen is False and given.new_model.controlled == moved
    extra = next(c for c in ("x", "y", "z", "roll", "pitch", "yaw") if c not in moved)
    with pytest.raises(ValueError, match=r"independently at home \(rank %d of %d\): they move %d end-effector DOF, "
                                         r"for example %s " % (len(moved), len(moved) + 1, len(moved), " ".join(moved))) as e:
        ccma.import_robot(os.path.join(folder, "robot.urdf"), controlled=moved + [extra], **files)
    refused = run_tool("import", "--from=" + os.path.join(folder, "robot.urdf"), "--closures=" + files["closures"],
                       "--end_effector=" + end_effector, "--controlled=" + ",".join(moved + [extra]),
                       "--out=" + str(tmp_path / "refused.yaml"), expect=2)
    assert refused.stdout == ""
    assert refused.stderr == "ccma import: " + str(e.value) + "\n"


def test_collision_radius_writes_the_same_capsules_as_the_cli(tmp_path):
    """collision_radius= is --collision_radius: the same JSON (capsule and ignored-pair
    counts), the same model file, and a model whose capsules obstacles are measured
    against; a radius out of [1e-4, 10] m (other than 0) is a ValueError."""
    folder = os.path.join(ROBOTS, "5bar_linkage")
    urdf, closures = os.path.join(folder, "robot.urdf"), os.path.join(folder, "robot.yaml")
    imported = ccma.import_robot(urdf, closures=closures, end_effector="effector", collision_radius=0.02,
                                 out=str(tmp_path / "py.yaml"))
    cli = run_tool("import", "--from=" + urdf, "--closures=" + closures, "--end_effector=effector",
                   "--collision_radius=0.02", "--out=" + str(tmp_path / "cli.yaml"))
    assert imported.collision_capsules == cli["collision_capsules"] == 10
    assert imported.collision_ignored_pairs == cli["collision_ignored_pairs"] == 3
    assert (tmp_path / "py.yaml").read_text() == (tmp_path / "cli.yaml").read_text()
    clearance = ccma.clearance(ccma.ForwardProblem(imported.new_model))
    assert clearance is not None and clearance.min >= clearance.margin
    plain = ccma.import_robot(urdf, closures=closures, end_effector="effector")
    assert plain.collision_capsules is None and ccma.clearance(ccma.ForwardProblem(plain.new_model)) is None
    for bad in (-0.01, float("nan"), 11.0, 1e-5):
        with pytest.raises(ValueError, match="collision_radius"):
            ccma.import_robot(urdf, closures=closures, end_effector="effector", collision_radius=bad)


def test_unknown_actuated_joint_raises_model_error():
    folder = os.path.join(ROBOTS, "5bar_linkage")
    with pytest.raises(ccma.ModelError, match="mot9"):
        ccma.import_robot(os.path.join(folder, "robot.urdf"), closures=os.path.join(folder, "robot.yaml"),
                          actuated=["mot9"], end_effector="effector")


def test_mesh_paths_are_written_relative_to_the_model_file(tmp_path):
    """import_robot(out=) names meshes relative to the model file's folder, never by an
    absolute path (package:///, file://, package://PKG/../ are all resolved first), so that
    the model and its meshes move together; a mesh outside that folder gets ../ parts."""
    import re
    import shutil
    robot = tmp_path / "robot"
    shutil.copytree(os.path.join(ROBOTS, "5bar_linkage"), robot)
    options = dict(closures=str(robot / "robot.yaml"), end_effector="effector")
    (tmp_path / "elsewhere").mkdir()
    for out, prefix in ((robot / "5bar.yaml", ""), (tmp_path / "5bar.yaml", "robot/"),
                        (tmp_path / "elsewhere" / "5bar.yaml", "../robot/")):
        ccma.import_robot(str(robot / "robot.urdf"), out=str(out), **options)
        files = re.findall(r'\{file: "([^"]*)"', out.read_text())
        assert files and all(f.startswith(prefix) and not f[len(prefix):].startswith("../") for f in files), files
        assert str(tmp_path) not in " ".join(files)
        assert prefix + "built.stl" in files


def test_repeated_or_unknown_controlled_components_are_refused():
    """issue 34: controlled=["x", "x"] is a typo, refused as `ccma import
    --controlled=x,x` is (the same check, analyses/internal/robot_model_builder.cc)."""
    folder = os.path.join(ROBOTS, "5bar_linkage")
    args = dict(closures=os.path.join(folder, "robot.yaml"), end_effector="effector")
    with pytest.raises(ccma.ModelError, match=r"controlled component 'x' given twice"):
        ccma.import_robot(os.path.join(folder, "robot.urdf"), controlled=["x", "x"], **args)
    with pytest.raises(ccma.ModelError, match=r"unknown controlled component 'w'"):
        ccma.import_robot(os.path.join(folder, "robot.urdf"), controlled=["x", "w"], **args)
    with pytest.raises(ValueError, match=r"controlled: empty or overlong name"):
        ccma.import_robot(os.path.join(folder, "robot.urdf"), controlled=["x" * 300], **args)
    with pytest.raises(ValueError, match=r"actuated: empty or overlong name"):
        ccma.import_robot(os.path.join(folder, "robot.urdf"), actuated=[""], **args)


def test_markup_that_hides_deep_nesting_raises_instead_of_crashing(tmp_path):
    # Issue 34: TinyXML ends `<?x >` at the first '>', the nesting check used to
    # skip to the next '?>': 100,000 nested elements after it overflowed the
    # stack and killed the interpreter.
    deep = "<a>" * 100000
    for name, root in (("deep.urdf", '<robot name="r"/>'), ("deep.sdf", '<sdf version="1.7"/>')):
        path = tmp_path / name
        path.write_text("<?x >" + deep + "<!-- ?> -->" + root)
        with pytest.raises(ccma.ModelError, match=name + r":1: expected the root element .* processing instruction"):
            ccma.import_robot(str(path), end_effector="a")


def test_a_long_name_is_quoted_short_with_control_bytes_escaped():
    folder = os.path.join(ROBOTS, "5bar_linkage")
    name = "\x1b[31m\nfake line" + "m" * 10_000_000
    with pytest.raises(ValueError) as error:  # refused as overlong before the robot is read
        ccma.import_robot(os.path.join(folder, "robot.urdf"), closures=os.path.join(folder, "robot.yaml"),
                          actuated=[name], end_effector="effector")
    message = str(error.value)
    assert len(message) < 1000
    assert "'\\x1b[31m\\x0afake line" in message and f"({len(name)} bytes)" in message
    assert "\x1b" not in message and "\n" not in message


@pytest.mark.parametrize("planted", [True, False], ids=["planted-link", "fresh-home"])
def test_an_sdformat_import_writes_nothing_under_home(tmp_path, planted):
    """issue 49: libsdformat's console opened $HOME/.sdformat/sdformat.log with
    O_TRUNC, through a link planted there. The import runs in a fresh
    interpreter (the console is made once per process) with HOME in tmp_path:
    the link's target is intact, and a home without .sdformat stays empty."""
    import subprocess
    import sys
    home, victim = tmp_path / "home", tmp_path / "victim.txt"
    home.mkdir()
    if planted:
        (home / ".sdformat").mkdir()
        victim.write_text("precious\n")
        (home / ".sdformat" / "sdformat.log").symlink_to(victim)
    robot = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data", "four_bar_loop.sdf")
    script = (f"import ccma; ccma.import_robot({robot!r}, actuated=['crank'], end_effector='coupler', "
              f"out={str(tmp_path / 'robot.yaml')!r})")
    run = subprocess.run([sys.executable, "-c", script], env=dict(os.environ, HOME=str(home)), capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert (tmp_path / "robot.yaml").exists()
    if planted:
        assert victim.read_text() == "precious\n" and (home / ".sdformat" / "sdformat.log").is_symlink()
    else:
        assert list(home.iterdir()) == []
    assert "HOME" not in run.stderr


def test_closure_gaps_and_motor_moves_are_reported_and_strict_refuses_them():
    folder = os.path.join(ROBOTS, "5bar_linkage")
    args = dict(closures=os.path.join(folder, "robot.yaml"), end_effector="effector")
    with pytest.warns(UserWarning, match=r"closure 'closedloop1_A__closedloop1_B': its frames are 0.3 m and 1.5708 rad"):
        imported = ccma.import_robot(os.path.join(folder, "robot.urdf"), **args)
    gap = imported.closure_gaps[0]
    assert gap.name == "closedloop1_A__closedloop1_B"
    assert abs(gap.gap_m - 0.3) < 1e-12 and abs(gap.gap_rad - math.pi / 2) < 1e-12
    assert [m.move for m in imported.motor_moves] == [0.0, 0.0]  # the passive joints close it
    with pytest.raises(ccma.ModelError, match=r"--strict: the import would change the mechanism: closure"):
        ccma.import_robot(os.path.join(folder, "robot.urdf"), strict=True, **args)
