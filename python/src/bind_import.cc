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
#include "documents/export_document.h"
#include "documents/import_document.h"
#include "ccma/internal/format.h"
#include "formats/internal/sdformat_console.h"
#include "formats/robot_file.h"
#include "formats/sdformat_reader.h"
#include "python/src/bindings.h"
#include "python/src/json_to_python.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

// (model, model file text, `ccma import`'s JSON without "out"); the Python
// wrapper (ccma/robots.py) writes `out`. The warnings the command prints on
// stderr are UserWarnings.
py::tuple ImportRobotFile(const std::filesystem::path& from, const std::optional<std::filesystem::path>& closures,
                          const std::vector<std::string>& actuated, const std::string& end_effector,
                          const Eigen::Vector3d& point, const std::vector<std::string>& controlled,
                          const std::optional<std::filesystem::path>& model_folder, double collision_radius,
                          bool strict, const std::string& keyframe) {
  const std::string path = from.string();
  ImportOptions options;
  options.actuated = actuated;
  options.end_effector_link = end_effector;
  options.end_effector_point_L = point;
  options.controlled = controlled;
  if (model_folder) options.model_folder = model_folder->string();  // mesh paths relative to it
  options.collision_radius = collision_radius;
  options.strict = strict;
  std::string why;
  if (!options.IsValid(&why)) throw py::value_error(why);
  RobotFileFormat format = RobotFileFormatOf(path);
  if (format == RobotFileFormat::kUnknown) format = RobotFileFormat::kUrdf;  // read as URDF, as it always was
  ImportedRobot imported;
  std::vector<std::string> warnings;
  {
    py::gil_scoped_release release;
    const RobotDescription robot = ReadRobotFile(path, format, closures ? closures->string() : "", actuated, keyframe);
    warnings = robot.warnings;
    imported = ImportRobot(robot, options);
  }
  const documents::Document document = documents::ImportDocument(imported, options);
  warnings.insert(warnings.end(), document.warnings.begin(), document.warnings.end());
  for (const std::string& w : warnings) {
    if (PyErr_WarnEx(PyExc_UserWarning, ("import: " + w).c_str(), 1) < 0) throw py::error_already_set();
  }
  return py::make_tuple(imported.model, imported.yaml, ToPython(document.json));
}

// `ccma export` without the files: its JSON (without "out") and "files", the
// (path, text) pairs to write, last to first (ccma/robots.py writes them).
py::dict ExportModel(const Model& model, const std::string& format, const std::string& out) {
  if (!documents::IsExportFormat(format)) {
    throw py::value_error(std::string("export: format must be ") + documents::kExportFormats);
  }
  const documents::Export exported = documents::ExportModel(model, format, out);
  py::dict d = ToPython(exported.document.json);
  py::list files;
  for (const documents::ExportedFile& f : exported.files) files.append(py::make_tuple(f.path, f.text));
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
        py::arg("model_folder") = py::none(), py::arg("collision_radius") = 0.0, py::arg("strict") = false,
        py::arg("keyframe") = "",
        "Private: ccma.import_robot. Converts a URDF (with its closure file, the example-parallel-robots convention) or an "
        "SDFormat file into a Model assembled at home, as `ccma import` (docs/import.md): "
        "actuated: joint names (URDF default: the closure file's name_mot); end_effector: the "
        "link carrying it and point its controlled point in that link's frame [m]; controlled: "
        "components (default: the stored ones, else those the motors move at home, translations first; "
        "refused when the motors cannot move them); model_folder: the folder the model file will be written to "
        "(mesh paths are written relative to it; default the robot file's folder); collision_radius: > 0 gives every "
        "body capsules of that radius [m] between its joint points (--collision_radius); strict: refuse an import that joins a closure's frames that are apart or moves a motor by more "
        "than 1e-6 (--strict). Returns (Model, model file text, "
        "`ccma import`'s JSON without out). Every joint's q "
        "equals the source's joint position (q_home). Raises ccma.ModelError naming the file, "
        "the element and the name.");
}

}  // namespace ccma::python
