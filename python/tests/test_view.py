"""ccma.view writes the page `ccma view` writes (same bytes), returns the HTML
outside Jupyter, and refuses bad input with ccma.ViewInputError."""
import os
import stat

import pytest

import ccma
from conftest import ROOT, run_tool

MODEL = ROOT / "models" / "4dof_reduced.yaml"


def test_view_matches_the_cli(tmp_path):
    waypoints = ROOT / "models" / "paths" / "4dof_sequential.csv"
    csv = tmp_path / "path.csv"
    run_tool("trajectory", "--model=%s" % MODEL, "--waypoints=%s" % waypoints, "--out=%s" % csv)
    cli = run_tool("view", "--model=%s" % MODEL, "--trajectory=%s" % csv, "--out=%s" % (tmp_path / "cli.html"))
    out = ccma.view(MODEL, trajectory=csv, out=tmp_path / "py.html")
    assert out.out == str(tmp_path / "py.html")
    assert (tmp_path / "py.html").read_bytes() == (tmp_path / "cli.html").read_bytes()
    page, info = ccma.view_html(ccma.load_model(MODEL), str(csv))
    assert info.frames == cli["frames"] and info.source == "trajectory"
    assert len(page.encode()) == cli["bytes"] == info.bytes


def test_view_returns_the_page_outside_jupyter():
    page = ccma.view(ccma.load_model(MODEL))
    assert page.startswith("<!DOCTYPE html>")
    assert "default-src 'none'" in page
    assert '"format":"ccma-scene-1"' in page


def test_view_refuses_bad_files(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("time_s,x_m\n0,1\n")
    with pytest.raises(ccma.ViewInputError, match="bad.csv"):
        ccma.view(MODEL, trajectory=bad)
    with pytest.raises(ValueError):
        ccma.view_html(ccma.load_model(MODEL), str(bad), str(tmp_path))


def test_view_displays_inline_in_jupyter(monkeypatch):
    """Inside a Jupyter kernel (a fake IPython here: Jupyter is not a
    dependency), ccma.view displays the page in an iframe instead of
    returning it."""
    import html
    import sys
    import types

    shown = []
    ipython = types.ModuleType("IPython")
    display = types.ModuleType("IPython.display")

    class Kernel:
        kernel = object()

    ipython.get_ipython = lambda: Kernel()
    display.HTML = lambda text: ("HTML", text)
    display.display = shown.append
    monkeypatch.setitem(sys.modules, "IPython", ipython)
    monkeypatch.setitem(sys.modules, "IPython.display", display)
    assert ccma.view(MODEL, height=400) is None
    assert len(shown) == 1 and shown[0][0] == "HTML"
    frame = shown[0][1]
    assert frame.startswith('<iframe srcdoc="') and "height:400px" in frame
    assert html.unescape(frame[len('<iframe srcdoc="'):frame.index('" style=')]).startswith("<!DOCTYPE html>")


def test_view_draws_a_workspace_map_like_the_cli(tmp_path):
    """ccma.view(workspace=...) writes the same page as `ccma view --workspace`,
    counts the map's rows and reachable rows as the CSV has them, and refuses
    a map together with a trajectory."""
    csv = tmp_path / "ws.csv"
    run_tool("workspace", "--model=%s" % MODEL, "--out=%s" % csv, "--x=-0.3:0.3", "--z=0.5:0.9",
             "--resolution=5")
    rows = csv.read_text().splitlines()
    header = rows[0].split(",")
    reachable = sum(int(r.split(",")[header.index("reachable")]) for r in rows[1:])
    cli = run_tool("view", "--model=%s" % MODEL, "--workspace=%s" % csv, "--out=%s" % (tmp_path / "cli.html"))
    assert ccma.view(MODEL, workspace=csv, out=tmp_path / "py.html").out == str(tmp_path / "py.html")
    assert (tmp_path / "py.html").read_bytes() == (tmp_path / "cli.html").read_bytes()
    _page, info = ccma.view_html(ccma.load_model(MODEL), workspace=str(csv))
    assert info.source == "workspace"
    assert info.workspace_points == len(rows) - 1 == cli["workspace_points"] == 25
    assert info.workspace_reachable == reachable == cli["workspace_reachable"]
    assert 0 < reachable < 25
    with pytest.raises(ValueError, match="one of"):
        ccma.view(MODEL, trajectory=csv, workspace=csv)


def test_view_bounds_the_work_of_far_jumps(tmp_path):
    # Bases 2 km (100,000 assembly sub-steps) away from the last frame assembled:
    # not attempted, flagged and counted (docs/viewer.md, "Work bound").
    model = ccma.load_model(MODEL)
    home = model.home_controls
    csv = tmp_path / "jumping.csv"
    header = ["time_s"] + [f"u{k}_{c}" for k in range(3) for c in ("x_m", "y_m", "theta_rad")]
    header += ["target_x_m", "target_y_m", "target_z_m", "x_m", "y_m", "z_m", "reached"]
    rows = [",".join(header)]
    for i, shift in enumerate([0.0, 2000.0, 0.0]):
        u = [home[j] + (shift if j % 3 == 0 else 0.0) for j in range(9)]
        rows.append(",".join(repr(float(v)) for v in [i] + u + [shift, 0, 0.6, shift, 0, 0.6, 1]))
    csv.write_text("\n".join(rows) + "\n")
    _, info = ccma.view_html(model, str(csv))
    assert info.frames == 3
    assert info.beyond_work_bound_frames == 1
    assert info.not_assembled_frames == 1 and info.flagged_frames == 1
    assert "beyond_work_bound_frames" not in ccma.view_html(model)[1].to_dict()


def test_view_out_replaces_the_file_safely(tmp_path):
    """out= keeps the replaced file's mode, follows a link to its target (the
    link stays a link), never writes through a link planted beside it, and
    leaves no temporary behind."""
    out = tmp_path / "page.html"
    out.write_text("old")
    os.chmod(out, 0o600)
    victim = tmp_path / "victim"
    victim.write_text("secret")
    # A link at the name an in-place or predictable writer would open.
    (tmp_path / ("page.html.partial.%d" % os.getpid())).symlink_to(victim)
    before = os.stat(out).st_ino
    assert ccma.view(MODEL, out=out).out == str(out)
    assert os.stat(out).st_ino != before  # replaced, never rewritten in place
    assert stat.S_IMODE(os.stat(out).st_mode) == 0o600
    assert out.read_text(encoding="utf-8") == ccma.view(ccma.load_model(MODEL))
    assert victim.read_text() == "secret"
    link = tmp_path / "link.html"
    link.symlink_to(out)
    ccma.view(MODEL, out=link)
    assert link.is_symlink() and out.read_text(encoding="utf-8").startswith("<!DOCTYPE html>")
    assert not [p.name for p in tmp_path.iterdir() if "ccma-tmp" in p.name]
    assert stat.S_IMODE(os.stat(out).st_mode) == 0o600


def test_view_draws_meshes_like_the_cli(tmp_path):
    """ccma.view(meshes=True) writes the same page as `ccma view --meshes`
    (the STL files found beside the model file), and a missing mesh raises
    ccma.ViewInputError naming the model file, the body and the mesh file."""
    model = ROOT / "tests" / "meshes" / "four_bar_meshes.yaml"
    cli = run_tool("view", "--model=%s" % model, "--meshes", "--out=%s" % (tmp_path / "cli.html"))
    assert cli["mesh_files"] == 2
    ccma.view(model, meshes=True, out=tmp_path / "py.html")
    assert (tmp_path / "py.html").read_bytes() == (tmp_path / "cli.html").read_bytes()
    assert '"stl_base64"' not in ccma.view(model)  # the scene's key (the script names it unquoted)
    lonely = tmp_path / "four_bar_meshes.yaml"
    lonely.write_text(model.read_text())  # no STL files beside this copy
    with pytest.raises(ccma.ViewInputError, match=r"four_bar_meshes.yaml:11: body 'crank': mesh 'box.stl'"):
        ccma.view(lonely, meshes=True)


def test_view_reads_meshes_only_inside_the_models_folder_or_mesh_root(tmp_path):
    """A mesh reached through a symlink shipped beside the model (pointing outside its
    folder) raises ccma.ViewInputError naming the file, line, body and mesh, as
    `ccma view --meshes` exits 2; mesh_root= (a folder or a list) allows its folder,
    as --mesh_root does, and the page holds no absolute path."""
    source = ROOT / "tests" / "meshes"
    folder, outside = tmp_path / "model", tmp_path / "outside"
    folder.mkdir()
    outside.mkdir()
    model = folder / "four_bar_meshes.yaml"
    model.write_text((source / "four_bar_meshes.yaml").read_text())
    (folder / "box.stl").write_bytes((source / "box.stl").read_bytes())
    (outside / "tetra.stl").write_bytes((source / "tetra.stl").read_bytes())
    (folder / "tetra.stl").symlink_to(outside / "tetra.stl")
    with pytest.raises(ccma.ViewInputError, match=r"four_bar_meshes.yaml:14: body 'coupler': mesh 'tetra.stl': "
                                                  r"outside the model file's folder"):
        ccma.view(model, meshes=True)
    cli = run_tool("view", "--model=%s" % model, "--meshes", "--mesh_root=%s" % outside,
                   "--out=%s" % (tmp_path / "cli.html"))
    assert cli["mesh_files"] == 2
    for roots in (outside, str(outside), [outside]):
        ccma.view(model, meshes=True, mesh_root=roots, out=tmp_path / "py.html")
        assert (tmp_path / "py.html").read_bytes() == (tmp_path / "cli.html").read_bytes()
        assert str(tmp_path) not in (tmp_path / "py.html").read_text(encoding="utf-8")
    with pytest.raises(ccma.ViewInputError, match="mesh root '.*nope': not an existing folder"):
        ccma.view(model, meshes=True, mesh_root=tmp_path / "nope")
    with pytest.raises(ValueError, match="mesh_root goes with meshes=True"):
        ccma.view_html(ccma.load_model(str(model)), mesh_root=[str(outside)])


def test_view_colours_by_load_like_the_cli(tmp_path):
    """ccma.view(color_by="load") writes the page of `ccma view --color_by=load`;
    view_html reports the largest load: the tripod's legs carry W sqrt(2) / 3."""
    model = ROOT / "examples" / "statics" / "tripod.yaml"
    cli = run_tool("view", "--model=%s" % model, "--color_by=load", "--out=%s" % (tmp_path / "cli.html"))
    ccma.view(model, color_by="load", out=tmp_path / "py.html")
    assert (tmp_path / "py.html").read_bytes() == (tmp_path / "cli.html").read_bytes()
    _page, info = ccma.view_html(ccma.load_model(str(model)), color_by="load")
    assert info.max_load == pytest.approx(3 * 9.81 * 2 ** 0.5 / 3, rel=1e-6)
    assert info.max_load == pytest.approx(cli["max_load"], rel=1e-12)
    with pytest.raises(ValueError, match="color_by"):
        ccma.view_html(ccma.load_model(str(model)), color_by="stress")


def test_view_draws_the_loaded_shape_like_the_cli(tmp_path):
    compliant = ROOT / "examples" / "statics" / "stewart_gough_compliant.yaml"
    args = dict(controls=[0.01, 0, 0, 0, 0, 0], deflection=50, wrench=[0, 0, -80, 0, 0, 0])
    cli = run_tool("view", "--model=%s" % compliant, "--controls=0.01,0,0,0,0,0", "--deflection=50",
                   "--wrench=0,0,-80,0,0,0", "--out=%s" % (tmp_path / "cli.html"))
    out = ccma.view(compliant, out=tmp_path / "py.html", **args)
    assert (tmp_path / "py.html").read_bytes() == (tmp_path / "cli.html").read_bytes()
    assert out.source == cli["source"] == "controls"
    assert out.deflection_scale == 50 and out.deflection_converged and out.load_fraction == 1
    assert out.max_deflection_m == cli["max_deflection_m"] > 1e-4
    # Without deflection= no such key; a rigid model, a bad scale or an animation refused.
    assert ccma.view_html(ccma.load_model(compliant))[1].deflection_scale is None
    for bad, kw in ((MODEL, dict(deflection=10)), (compliant, dict(deflection=0)),
                    (compliant, dict(deflection=float("nan"))), (compliant, dict(deflection=2e6)),
                    (compliant, dict(wrench=[0, 0, -1, 0, 0, 0])), (compliant, dict(deflection=5, color_by="load")),
                    (compliant, dict(controls=[0, 0]))):
        with pytest.raises(ValueError):
            ccma.view(bad, **kw)
