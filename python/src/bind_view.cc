// The 3D viewer's page from Python: ccma.view_html(model, trajectory=..., replay=..., workspace=..., meshes=...)
// (ccma.view in python/ccma/viewer.py writes it or shows it in Jupyter).
#include <cmath>
#include <optional>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "documents/view_document.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
#include "python/src/json_to_python.h"
#include "viewer/html.h"
#include "viewer/mesh_files.h"
#include "viewer/scene.h"
#include "viewer/view_frames.h"
#include "viewer/workspace_cloud.h"

namespace py = pybind11;

namespace ccma::python {

namespace {

// mesh_root=: None, one folder (str or os.PathLike) or an iterable of them.
std::vector<std::string> MeshRoots(const py::object& mesh_root) {
  std::vector<std::string> roots;
  if (mesh_root.is_none()) return roots;
  const py::object fspath = py::module_::import("os").attr("fspath");
  if (py::isinstance<py::str>(mesh_root) || py::hasattr(mesh_root, "__fspath__")) {
    roots.push_back(fspath(mesh_root).cast<std::string>());
    return roots;
  }
  for (const py::handle root : mesh_root) roots.push_back(fspath(root).cast<std::string>());
  return roots;
}

// controls= (a static view at those controls) and deflection= / wrench= (the
// loaded shape, `ccma view --controls --deflection --wrench`): checked as
// the command checks its flags. Returns the deflection request, if any.
std::optional<viewer::DeflectionRequest> StaticViewArguments(const Model& model,
                                                             const std::optional<Eigen::VectorXd>& controls,
                                                             const std::optional<double>& deflection,
                                                             const std::optional<Eigen::VectorXd>& wrench,
                                                             bool animated, const std::string& color_by) {
  if (controls && animated) throw py::value_error("controls is for a static view, without trajectory, replay or workspace");
  if (controls && controls->size() != model.num_controls()) {
    throw py::value_error("controls: model " + Quote(model.name) + " has " + std::to_string(model.num_controls()) +
                          " controls; got " + std::to_string(controls->size()));
  }
  if (controls && !(controls->array().abs() <= kMaxMagnitude).all()) {
    throw py::value_error("controls: every entry must be a finite number in [-1e4, 1e4] (m or rad)");
  }
  if (wrench && !deflection) throw py::value_error("wrench goes with deflection (the loads of the loaded shape)");
  if (!deflection) return std::nullopt;
  if (animated) throw py::value_error("deflection is for a static view, without trajectory, replay or workspace");
  if (color_by != "body") throw py::value_error("deflection colours the bodies itself: not with color_by='load'");
  if (!(*deflection > 0 && *deflection <= viewer::kMaxDeflectionScale)) {
    throw py::value_error("deflection: the scale must be a number in (0, 1e6], not " + FormatG(*deflection));
  }
  if (!model.compliant()) {
    throw py::value_error("deflection: model " + Quote(model.name) + " has no stiffness keys: it is rigid and nothing deflects");
  }
  return viewer::DeflectionRequest{*deflection, WrenchFrom(wrench, "view")};
}

// The frames to draw (none: the model at home) and their source.
std::vector<viewer::ViewFrame> ViewFramesFrom(const Model& model, const std::optional<std::string>& trajectory,
                                              const std::optional<std::string>& replay,
                                              const std::optional<Eigen::VectorXd>& controls, std::string* source) {
  if (trajectory) {
    *source = "trajectory";
    return viewer::FramesFromTrajectory(model, *trajectory);
  }
  if (replay) {
    *source = "replay";
    return viewer::FramesFromReplay(model, *replay);
  }
  if (!controls) return {};
  *source = "controls";
  return {{0.0, *controls, std::nullopt, std::nullopt, false}};
}

// view_html: the page and the summary `ccma view` prints (see BindView), as a
// ccma.ViewResult without "out" (ccma.view adds it when it writes the page).
py::tuple ViewHtml(const Model& model, std::optional<std::string> trajectory, std::optional<std::string> replay,
                   std::optional<std::string> workspace, bool meshes, const std::string& color_by,
                   const py::object& mesh_root, const std::optional<Eigen::VectorXd>& controls,
                   const std::optional<double>& deflection, const std::optional<Eigen::VectorXd>& wrench,
                   std::optional<std::string> dynamics) {
  const std::vector<std::string> roots = MeshRoots(mesh_root);
  if (!roots.empty() && !meshes) throw py::value_error("mesh_root goes with meshes=True");
  if (int(bool(trajectory)) + int(bool(replay)) + int(bool(workspace)) > 1) {
    throw py::value_error("give one of trajectory, replay or workspace");
  }
  if (color_by != "body" && color_by != "load") {
    throw py::value_error("color_by must be 'body' or 'load', not '" + color_by + "'");
  }
  if (dynamics && !trajectory) throw py::value_error("dynamics goes with trajectory (the trajectory its efforts are of)");
  if (dynamics && color_by != "body") throw py::value_error("dynamics colours the bodies by effort: not with color_by='load'");
  const std::optional<viewer::DeflectionRequest> loaded =
      StaticViewArguments(model, controls, deflection, wrench, trajectory || replay || workspace, color_by);
  const viewer::ColorBy colors = color_by == "load" ? viewer::ColorBy::kLoad : viewer::ColorBy::kBody;
  std::string html;
  viewer::SceneSummary summary;
  std::string source = "model";
  std::optional<viewer::MeshFiles> mesh_files;
  try {
    py::gil_scoped_release release;
    std::optional<viewer::WorkspaceCloud> cloud;
    if (meshes) mesh_files = viewer::ReadMeshFiles(model, roots);  // confined to model.source's folder and roots
    if (workspace) {
      // Drawn over the model at home, as `ccma view --workspace` does.
      cloud = viewer::CloudFromWorkspaceCsv(model, *workspace);
      source = "workspace";
    }
    const std::vector<viewer::ViewFrame> frames = ViewFramesFrom(model, trajectory, replay, controls, &source);
    std::optional<viewer::FrameEfforts> efforts;
    if (dynamics) efforts = viewer::ReadFrameEfforts(model, *dynamics, frames);
    html = viewer::ViewerHtml(viewer::BuildScene(model, frames, source, &summary, cloud ? &*cloud : nullptr,
                                                 mesh_files ? &*mesh_files : nullptr, colors,
                                                 loaded ? &*loaded : nullptr, efforts ? &*efforts : nullptr),
                              model.name);
  } catch (const viewer::DeflectionError& e) {
    throw py::value_error(std::string("deflection: ") + e.what());
  } catch (const std::invalid_argument& e) {  // no limits to colour the efforts by
    throw py::value_error(std::string("dynamics: ") + e.what());
  }
  const documents::Document document =
      documents::ViewDocument(model, summary, html.size(), source, mesh_files ? &*mesh_files : nullptr,
                              workspace.has_value(), colors == viewer::ColorBy::kLoad);
  return py::make_tuple(html, MakeResult("ViewResult", document.json));
}

}  // namespace

void BindView(py::module_& m) {
  py::register_exception<viewer::ViewInputError>(m, "ViewInputError", PyExc_ValueError).attr("__doc__") =
      "Raised by view and view_html when the trajectory CSV, replay directory or workspace CSV "
      "to draw cannot be read or is malformed (a missing column, an empty or out-of-range "
      "value, files of a replay that disagree). Carries one argument, the message naming the "
      "file, and the line and column where there is one, e.g. 'file:line: column 'name': what' "
      "(str(e), e.args[0]); with meshes=True, also a mesh file outside the allowed folders, "
      "missing or not a valid STL. A subclass of ValueError.";
  m.def("viewer_available", &viewer::HasBundle, "whether this build carries the viewer's JavaScript");
  m.def(
      "view_html", &ViewHtml, py::arg("model"), py::arg("trajectory") = py::none(), py::arg("replay") = py::none(),
      py::arg("workspace") = py::none(), py::arg("meshes") = false, py::arg("color_by") = "body",
      py::arg("mesh_root") = py::none(), py::arg("controls") = py::none(), py::arg("deflection") = py::none(),
      py::arg("wrench") = py::none(), py::arg("dynamics") = py::none(),
      "(html, info): the self-contained page of `ccma view` and its summary, a ccma.ViewResult (the command's "
      "JSON without out: bytes, frames, source, flagged_frames, ...), for the model, animated along a "
      "trajectory CSV or a replay directory, or with a `ccma workspace` CSV as a point cloud; "
      "meshes=True draws the bodies' STL meshes (`ccma view --meshes`), read only from inside the "
      "model file's folder (symlinks resolved) and the folders of mesh_root (a folder or a list: "
      "`--mesh_root`); color_by='load' colours "
      "the links by joint load (`ccma view --color_by=load`; info gains max_load [N], "
      "unbalanced_frames, indeterminate_frames); controls: a static view at those controls (source "
      "'controls'); deflection=SCALE: the loaded shape of a compliant model exaggerated SCALE times over the "
      "rigid one, under gravity, the payload and wrench (fx, fy, fz, mx, my, mz; `ccma view --deflection`; "
      "info gains deflection_scale, max_deflection_m [m], deflection_converged, load_fraction); "
      "dynamics: with trajectory, its `ccma dynamics --out` CSV: each actuator with a limit colours the body it "
      "drives by its effort as a share of the limit (`ccma view --dynamics`; info gains max_effort_share, "
      "effort_frames_beyond_limit); "
      "raises ccma.ViewInputError on a bad file, ValueError on bad arguments.");
}

}  // namespace ccma::python
