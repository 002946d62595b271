// Robots described elsewhere (analyses/robot_import.h): ccma.import_robot,
// the `ccma import` command without the file (unless out= is given).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "analyses/robot_import.h"
#include "documents/json_values.h"
#include "ccma/internal/format.h"
#include "formats/internal/sdformat_console.h"
#include "formats/sdformat_reader.h"
#include "formats/sdformat_writer.h"
#include "formats/urdf_reader.h"
#include "formats/urdf_writer.h"
#include "python/src/bindings.h"
#include "python/src/json_to_python.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The bounds `ccma import` puts on its --actuated and --controlled names
// (apps/import_command.cc): none empty, none longer than 256 bytes.
void CheckNames(const std::vector<std::string>& names, const char* what) {
  for (const std::string& name : names) {
    if (name.empty() || name.size() > 256) {
      throw py::value_error(std::string(what) + ": empty or overlong name " + Quote(name));
    }
  }
}

// (model, model file text, `ccma import`'s JSON without "out"); the Python
// wrapper (ccma/robots.py) writes `out`. The warnings the command prints on
// stderr are UserWarnings.
py::tuple ImportRobotFile(const std::filesystem::path& from, const std::optional<std::filesystem::path>& closures,
                          const std::vector<std::string>& actuated, const std::string& end_effector,
                          const Eigen::Vector3d& point, const std::vector<std::string>& controlled,
                          const std::optional<std::filesystem::path>& model_folder, double collision_radius) {
  const std::string path = from.string();
  const bool sdf = EndsWith(path, ".sdf") || EndsWith(path, ".world");
  if (sdf && closures) throw py::value_error("closures is for URDF (SDFormat holds its loops)");
  CheckNames(actuated, "actuated");
  CheckNames(controlled, "controlled");
  if (end_effector.size() > 256) throw py::value_error("end_effector: overlong name " + Quote(end_effector));
  if (!point.allFinite() || point.cwiseAbs().maxCoeff() > 1e4) throw py::value_error("point must be finite, within 1e4 m");
  ImportOptions options;
  options.actuated = actuated;
  options.end_effector_link = end_effector;
  options.end_effector_point_L = point;
  options.controlled = controlled;
  if (model_folder) options.model_folder = model_folder->string();  // mesh paths relative to it
  // apps/import_command.cc's range for --collision_radius.
  if (!(collision_radius == 0 || (collision_radius >= 1e-4 && collision_radius <= 10))) {
    throw py::value_error("collision_radius: must be 0 or in [1e-4, 10] m, got " + FormatG(collision_radius));
  }
  options.collision_radius = collision_radius;
  ImportedRobot imported;
  std::vector<std::string> warnings;
  {
    py::gil_scoped_release release;
    const RobotDescription robot = sdf ? ReadSdformat(path, actuated) : ReadUrdf(path, closures ? closures->string() : "");
    warnings = robot.warnings;
    imported = ImportRobot(robot, options);
    warnings.insert(warnings.end(), imported.warnings.begin(), imported.warnings.end());
  }
  for (const std::string& w : warnings) {
    if (PyErr_WarnEx(PyExc_UserWarning, ("import: " + w).c_str(), 1) < 0) throw py::error_already_set();
  }
  // apps/import_command.cc: the summary.
  nlohmann::json document = {{"bodies", imported.model.num_bodies()},
                                   {"joints", static_cast<int>(imported.model.joints.size())},
                                   {"closures", imported.closures},
                                   {"actuated", imported.actuated},
                                   {"controlled", imported.controlled},
                                   {"controlled_chosen", imported.controlled_chosen},
                                   {"assembled", true},
                                   {"residual_energy", imported.residual_energy},
                                   {"controls", documents::ToJson(imported.model.home_controls())}};
  if (collision_radius > 0) {
    document["collision_capsules"] = imported.collision_capsules;
    document["collision_ignored_pairs"] = imported.collision_ignored_pairs;
  }
  return py::make_tuple(imported.model, imported.yaml, ToPython(document));
}

// `ccma export` without the files: its JSON (without "out") and "files", the
// (path, text) pairs to write (ccma/robots.py writes them).
py::dict ExportModel(const Model& model, const std::string& format, const std::string& out) {
  if (format != "urdf" && format != "sdf") throw py::value_error("export: format must be 'urdf' or 'sdf'");
  py::dict d;
  py::list files;
  d["format"] = format;
  if (format == "urdf") {
    const UrdfExport urdf = WriteUrdf(model);
    const std::string closures = ClosureFilePath(out);
    files.append(py::make_tuple(closures, urdf.closures));
    files.append(py::make_tuple(out, urdf.urdf));
    d["closures"] = closures;
    d["links"] = urdf.links;
    d["joints"] = urdf.joints;
    d["loops"] = urdf.loops;
  } else {
    const SdformatExport sdf = WriteSdformat(model);
    files.append(py::make_tuple(out, sdf.sdf));
    d["closures"] = py::none();
    d["links"] = sdf.links;
    d["joints"] = sdf.joints;
    d["loops"] = sdf.loops;
  }
  d["files"] = files;
  return d;
}

}  // namespace

void BindImport(py::module_& m) {
  // libsdformat's console made now, without its $HOME/.sdformat/sdformat.log
  // (formats/internal/sdformat_console.h): at import, not at the first
  // SDFormat file, while the host program is least likely to read its
  // environment from another thread.
  internal::QuietSdformatConsole();
  m.def("_export", &ExportModel, py::arg("model"), py::arg("format"), py::arg("out"),
        "Internal: ccma.export (python/ccma/robots.py): `ccma export`'s JSON without out, and the files to "
        "write as (path, text) pairs.");
  m.def("_import_robot", &ImportRobotFile, py::arg("path"), py::arg("closures") = py::none(),
        py::arg("actuated") = std::vector<std::string>{}, py::arg("end_effector") = "",
        py::arg("point") = Eigen::Vector3d::Zero(), py::arg("controlled") = std::vector<std::string>{},
        py::arg("model_folder") = py::none(), py::arg("collision_radius") = 0.0,
        "Private: ccma.import_robot. Converts a URDF (with its closure file, the example-parallel-robots convention) or an "
        "SDFormat file into a Model assembled at home, as `ccma import` (docs/import.md): "
        "actuated: joint names (URDF default: the closure file's name_mot); end_effector: the "
        "link carrying it and point its controlled point in that link's frame [m]; controlled: "
        "components (default: the stored ones, else those the motors move at home, translations first; "
        "refused when the motors cannot move them); model_folder: the folder the model file will be written to "
        "(mesh paths are written relative to it; default the robot file's folder); collision_radius: > 0 gives every "
        "body capsules of that radius [m] between its joint points (--collision_radius). Returns (Model, model file text, "
        "`ccma import`'s JSON without out). Every joint's q "
        "equals the source's joint position (q_home). Raises ccma.ModelError naming the file, "
        "the element and the name.");
}

}  // namespace ccma::python
