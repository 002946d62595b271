"""ccma.view: the 3D viewer of `ccma view` from Python (and inline in Jupyter)."""
import html as _html
import os as _os

from . import _ccma


def _in_notebook():
    try:
        from IPython import get_ipython  # type: ignore
    except ImportError:
        return False
    shell = get_ipython()
    return shell is not None and hasattr(shell, "kernel")


def view(model, trajectory=None, replay=None, out=None, height=600, workspace=None):
    """Shows `model` (a ccma.Model or a model file path) in 3D.

    trajectory: a CSV written by `ccma trajectory` (or ControlProblem.follow
    saved the same way); replay: a directory written by `ccma replay`;
    workspace: a CSV written by `ccma workspace`, drawn as a point cloud of
    end-effector positions over the model at home (reachable points coloured
    by sigma_min, unreachable ones grey). Give at most one of the three.
    out: write the self-contained HTML page there and return its path.
    Without `out`, inside Jupyter the page is displayed inline (an iframe,
    `height` pixels); elsewhere the HTML text is returned.
    Raises ccma.ViewInputError on a bad trajectory, replay or workspace file.
    """
    if isinstance(model, (str, _os.PathLike)):
        model = _ccma.load_model(_os.fspath(model))
    page, _info = _ccma.view_html(model,
                                  None if trajectory is None else _os.fspath(trajectory),
                                  None if replay is None else _os.fspath(replay),
                                  None if workspace is None else _os.fspath(workspace))
    if out is not None:
        out = _os.fspath(out)
        with open(out, "w", encoding="utf-8") as f:
            f.write(page)
        return out
    if _in_notebook():
        from IPython.display import HTML, display  # type: ignore
        frame = ('<iframe srcdoc="%s" style="width:100%%;height:%dpx;border:0"></iframe>'
                 % (_html.escape(page, quote=True), int(height)))
        display(HTML(frame))
        return None
    return page
