"""ccma.view: the 3D viewer of `ccma view` from Python (and inline in Jupyter)."""
import html as _html
import os as _os
import stat as _stat
import tempfile as _tempfile

from . import _ccma


def _in_notebook():
    try:
        from IPython import get_ipython  # type: ignore
    except ImportError:
        return False
    shell = get_ipython()
    return shell is not None and hasattr(shell, "kernel")


def _final_target(path):
    """`path` with its symbolic links followed (the file they name may not
    exist yet): a link stays a link and its target gets the content."""
    for _ in range(40):
        if not _os.path.islink(path):
            return path
        link = _os.readlink(path)
        path = link if _os.path.isabs(link) else _os.path.join(_os.path.dirname(path), link)
    raise OSError("too many levels of symbolic links in %r" % path)


def _write_replacing(path, data):
    """Writes `data` to `path` as the `ccma` tool writes its outputs
    (apps/output_file.h): a device or FIFO in place; otherwise a fresh
    temporary `.NAME.ccma-tmp-<pid>-XXXXXXXX` beside it (tempfile.mkstemp: O_CREAT |
    O_EXCL, so a link planted there is never followed), given the replaced
    file's mode (else 0666 less the umask), fsync'ed and renamed over it, so
    nothing is half-written. On failure the temporary is removed."""
    target = _final_target(path)
    try:
        info = _os.stat(target)
    except FileNotFoundError:
        info = None
    if info is not None and _stat.S_ISDIR(info.st_mode):
        raise IsADirectoryError("%r is a directory" % path)
    if info is not None and not _stat.S_ISREG(info.st_mode):
        with open(target, "wb") as f:
            f.write(data)
        return
    if info is not None:
        mode = _stat.S_IMODE(info.st_mode)
    else:
        mask = _os.umask(0)
        _os.umask(mask)
        mode = 0o666 & ~mask
    folder, name = _os.path.split(target)
    fd, temporary = _tempfile.mkstemp(prefix=".%s.ccma-tmp-%d-" % (name, _os.getpid()), dir=folder or ".")
    try:
        with _os.fdopen(fd, "wb") as f:
            _os.fchmod(f.fileno(), mode)
            f.write(data)
            f.flush()
            _os.fsync(f.fileno())
        _os.replace(temporary, target)
    except BaseException:
        try:
            _os.unlink(temporary)
        except FileNotFoundError:
            pass
        raise


def view(model, trajectory=None, replay=None, out=None, height=600, workspace=None, meshes=False,
         color_by="body", mesh_root=None, controls=None, deflection=None, wrench=None, dynamics=None):
    """Shows `model` (a ccma.Model or a model file path) in 3D.

    trajectory: a CSV written by `ccma trajectory` (or ControlProblem.follow
    saved the same way); replay: a directory written by `ccma replay`;
    workspace: a CSV written by `ccma workspace`, drawn as a point cloud of
    end-effector positions over the model at home (reachable points coloured
    by sigma_min, unreachable ones grey). Give at most one of the three.
    meshes: draw the bodies' STL meshes (`meshes:` in the model; files
    relative to the folder of the model's file), as `ccma view --meshes`.
    They are read only from inside the model file's folder (symlinks
    resolved); mesh_root: a folder, or a list of folders, that meshes may
    also come from (`--mesh_root`). The page names each mesh relative to
    the model's folder, or by its file name, never by an absolute path.
    color_by: "load" colours the links by their largest joint reaction force
    under the model's masses and payload, as `ccma view --color_by=load`.
    controls: the model assembled at these controls (a static view, source
    'controls'), as `ccma view --controls`. deflection: SCALE in (0, 1e6], a
    compliant model's loaded shape (the loaded equilibrium of
    ForwardProblem.assemble(u, loaded=True)) drawn over the rigid one with its
    displacements multiplied by SCALE, each body coloured by its deflection,
    under gravity, the payload and wrench (fx, fy, fz [N], mx, my, mz [N*m],
    world frame), as `ccma view --deflection=SCALE --wrench=...`; at home or
    at `controls`. ValueError for a rigid model, a bad scale, or with a
    trajectory, replay, workspace or color_by="load".
    dynamics: with trajectory, its `ccma dynamics --out` CSV (or
    ccma.dynamics(..., out=PATH)): every actuator with an effort_limits or
    push_limit colours the body it drives by its effort as a share of the
    limit, magenta beyond it, as `ccma view --dynamics`.
    out: write the self-contained HTML page there and return a ccma.ViewResult,
    the JSON `ccma view` prints as attributes (out, bytes, frames, source,
    flagged_frames, ...; to_dict() is that JSON). Without `out`, inside Jupyter
    the page is displayed inline (an iframe, `height` pixels); elsewhere the
    HTML text is returned.
    Raises ccma.ViewInputError on a bad trajectory, replay, workspace or mesh
    file, a mesh outside the allowed folders, or a mesh_root that is not a folder.
    """
    if isinstance(model, (str, _os.PathLike)):
        model = _ccma.load_model(_os.fspath(model))
    page, info = _ccma.view_html(model,
                                  None if trajectory is None else _os.fspath(trajectory),
                                  None if replay is None else _os.fspath(replay),
                                  None if workspace is None else _os.fspath(workspace),
                                  bool(meshes), str(color_by), mesh_root,
                                  None if controls is None else [float(v) for v in controls],
                                  None if deflection is None else float(deflection),
                                  None if wrench is None else [float(v) for v in wrench],
                                  None if dynamics is None else _os.fspath(dynamics))
    if out is not None:
        out = _os.fspath(out)
        _write_replacing(out, page.encode("utf-8"))
        document = info.to_dict()
        document["out"] = out
        return type(info)(document)
    if _in_notebook():
        from IPython.display import HTML, display  # type: ignore
        frame = ('<iframe srcdoc="%s" style="width:100%%;height:%dpx;border:0"></iframe>'
                 % (_html.escape(page, quote=True), int(height)))
        display(HTML(frame))
        return None
    return page
