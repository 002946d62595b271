"""Robots described elsewhere: ccma.import_robot (docs/import.md)."""
import os as _os

from . import _ccma
from .viewer import _write_replacing


def import_robot(path, closures=None, actuated=(), end_effector="", point=(0.0, 0.0, 0.0),
                 controlled=(), out=None):
    """Converts a URDF (with its closure file, the example-parallel-robots convention) or an
    SDFormat file into a ccma.Model assembled at home, as `ccma import` does.

    path: the .urdf or .sdf file; closures: the URDF's closure file (closed_loop, type,
    name_mot); actuated: joint names (URDF default: the closure file's name_mot);
    end_effector: the link that carries it (default: the one `ccma export` stored) and
    point its controlled point in that link's frame [m]; controlled: components among
    x, y, z, roll, pitch, yaw (default: the ones `ccma export` stored, else those the
    motors move at home, translations first, as `ccma import` chooses them; the model's
    `controlled` lists them); components the motors cannot move independently at home
    raise ccma.ModelError naming those they move. out: also write the model file there
    (replaced atomically, never through a planted link). Every joint's q equals the
    source's joint position (q_home). Mesh paths are written relative to the folder of
    `out` (without `out`: of the robot file), so that the model and its meshes move
    together; `ccma.view(meshes=True)` reads meshes outside the model's folder only with
    mesh_root=. Raises ccma.ModelError naming the file, the element
    and the name."""
    folder = None if out is None else _os.path.dirname(_os.path.abspath(_os.fspath(out)))
    model, text = _ccma._import_robot(path, closures, list(actuated), end_effector, point, list(controlled),
                                      folder)
    if out is None:
        return model
    _write_replacing(out, text.encode("utf-8"))
    return _ccma.load_model(out)
