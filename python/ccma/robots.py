"""Robots described elsewhere: ccma.import_robot and ccma.export (docs/import.md)."""
import os as _os

from . import _ccma
from ._tables import out_path
from .results import ExportResult, ImportResult
from .viewer import _write_replacing


def _end_effector(text):
    """`--end_effector=LINK[:px,py,pz]` -> (link, point [m]), with the command's checks."""
    link, point = text, (0.0, 0.0, 0.0)
    if ":" in text:
        link, numbers = text.rsplit(":", 1)
        try:
            point = tuple(float(v) for v in numbers.split(","))
        except ValueError:
            raise ValueError("end_effector: the point needs 3 numbers (LINK:px,py,pz) [m], got %r"
                             % numbers[:64]) from None
        if len(point) != 3:
            raise ValueError("end_effector: the point needs 3 numbers (LINK:px,py,pz) [m]")
    return link, point


def import_robot(from_, closures=None, actuated=(), end_effector="", controlled=(), collision_radius=0.0, out=None,
                 strict=False, keyframe=""):
    """`ccma import`: a URDF (with its closure file, the example-parallel-robots convention),
    an SDFormat file or a MuJoCo MJCF file (an .xml with a <mujoco> root) as a ccma model
    assembled at home.

    from_: the .urdf, .sdf, .world or .xml file (--from; `from` is a Python keyword); keyframe:
    an MJCF file's keyframe to read the robot at (--keyframe; default its qpos0); closures: the URDF's
    closure file (closed_loop, type, name_mot); actuated: joint names (URDF default: the
    closure file's name_mot); end_effector: 'LINK' or 'LINK:px,py,pz', the link that carries
    it and the controlled point in that link's frame [m] (default: the one `ccma export`
    stored); controlled: components among x, y, z, roll, pitch, yaw (default: the ones
    `ccma export` stored, else those the motors move at home, translations first, as
    `ccma import` chooses them); components the motors cannot move independently at home
    raise ccma.ModelError naming those they move; collision_radius: > 0 gives every body
    capsules of that radius [m] along the segments between its joint points, so that
    obstacles and clearance apply (0 or [1e-4, 10] m; --collision_radius,
    docs/import.md#collision-geometry); out: also write the model file there (replaced
    atomically, never through a planted link); strict: raise ccma.ModelError instead of
    joining a closure's frames that are apart in the source or moving a motor from its source
    position by more than 1e-6 (--strict).

    Returns a ccma.ImportResult: the command's JSON as attributes (to_dict()): bodies,
    joints, closures, actuated, controlled (the model's components), controlled_chosen
    (True when import chose them), assembled, residual_energy [m^2], controls, closure_gaps
    ({name, gap_m, gap_rad} per closure, in the source), motor_moves ({name, move} per motor,
    rad or m, from its source position to home),
    collision_capsules and collision_ignored_pairs with collision_radius, and out when
    written; `new_model` is the imported Model (as loaded back from `out` when written).
    Every joint's q equals the source's joint position (q_home). Mesh paths are written
    relative to the folder of `out` (without `out`: of the robot file), so that the model
    and its meshes move together. The command's warnings are UserWarnings. Raises
    ccma.ModelError naming the file, the element and the name."""
    out = out_path(out)
    folder = None if out is None else _os.path.dirname(_os.path.abspath(out))
    link, point = _end_effector(str(end_effector))
    model, text, document = _ccma._import_robot(from_, closures, list(actuated), link, point, list(controlled),
                                                folder, float(collision_radius), bool(strict), str(keyframe))
    if out is not None:
        _write_replacing(out, text.encode("utf-8"))
        model = _ccma.load_model(out)
        document["out"] = out
    return ImportResult(document, new_model=model)


def export(model, format, out):
    """`ccma export`: writes the model as URDF (a spanning tree, with the joints that close
    its loops in a closure file beside it, OUT with the extension .closures.yaml) or as
    SDFormat (with its loops). `ccma.import_robot` of the output gives back the mechanism.

    model: a ccma.Model or a model file's path (as --model); format: 'urdf', 'sdf' or 'mjcf'
    (MuJoCo's XML, loops as equality constraints, written at the assembled home); out:
    the file to write (replaced atomically, never through a planted link). Returns a
    ccma.ExportResult: the command's JSON as attributes (to_dict()): out, format, closures
    (the closure file's path, None for sdf), links, joints, loops."""
    if isinstance(model, (str, _os.PathLike)):
        model = _ccma.load_model(_os.fspath(model))
    out = out_path(out)
    if out is None:
        raise ValueError("export: out names the file to write")
    files = _ccma._export(model, str(format), out)
    for path, text in reversed(files.pop("files")):  # the closure file before the URDF naming it
        _write_replacing(path, text.encode("utf-8"))
    files["out"] = out
    return ExportResult(files)
