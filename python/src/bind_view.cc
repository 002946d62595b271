// The 3D viewer's page from Python: ccma.view_html(model, trajectory=..., replay=...)
// (ccma.view in python/ccma/viewer.py writes it or shows it in Jupyter).
#include <optional>

#include <pybind11/stl.h>

#include "python/src/bindings.h"
#include "viewer/html.h"
#include "viewer/scene.h"
#include "viewer/view_frames.h"

namespace py = pybind11;

namespace ccma::python {

void BindView(py::module_& m) {
  py::register_exception<viewer::ViewInputError>(m, "ViewInputError", PyExc_ValueError);
  m.def("viewer_available", &viewer::HasBundle, "whether this build carries the viewer's JavaScript");
  m.def(
      "view_html",
      [](const Model& model, std::optional<std::string> trajectory, std::optional<std::string> replay) {
        if (trajectory && replay) throw py::value_error("give trajectory or replay, not both");
        std::string html;
        viewer::SceneSummary summary;
        std::string source = "model";
        {
          py::gil_scoped_release release;
          std::vector<viewer::ViewFrame> frames;
          if (trajectory) {
            frames = viewer::FramesFromTrajectory(model, *trajectory);
            source = "trajectory";
          } else if (replay) {
            frames = viewer::FramesFromReplay(model, *replay);
            source = "replay";
          }
          html = viewer::ViewerHtml(viewer::BuildScene(model, frames, source, &summary), model.name);
        }
        py::dict info;
        info["frames"] = summary.frames;
        info["flagged_frames"] = summary.flagged_frames;
        info["not_assembled_frames"] = summary.not_assembled;
        info["branch_jumps"] = summary.branch_jumps;
        info["source"] = source;
        return py::make_tuple(html, info);
      },
      py::arg("model"), py::arg("trajectory") = py::none(), py::arg("replay") = py::none(),
      "(html, info): the self-contained page of `ccma view` for the model, animated along a "
      "trajectory CSV or a replay directory; raises ccma.ViewInputError on a bad file.");
}

}  // namespace ccma::python
