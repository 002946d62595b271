// ccma.WorkBoundError and ccma._WorkEstimate (analyses/work_estimate.h): the
// bound on a run's estimated time, for ccma.workspace's tiles counted in
// Python (python/ccma/workspace.py) and, through PythonWorkEstimate, for
// the runs counted in C++ (the local map, the design loop).
#include <pybind11/pybind11.h>

#include "ccma/internal/format.h"
#include "python/src/bindings.h"
#include "python/src/work_bound.h"

namespace py = pybind11;

namespace ccma::python {

WorkEstimateOptions PythonWorkEstimate(const std::string& function, const std::string& noun, double max_minutes) {
  if (!(max_minutes > 0 && max_minutes <= kLargestMaxMinutes)) {
    throw py::value_error(function + ": max_minutes must lie in (0, " + FormatG(kLargestMaxMinutes) + "], got " +
                          FormatG(max_minutes));
  }
  WorkEstimateOptions options;
  options.who = "ccma." + function;
  options.noun = noun;
  options.max_minutes = max_minutes;
  options.raise_with = "max_minutes";
  options.say = [](const std::string& line) {
    const py::gil_scoped_acquire gil;
    const py::object err = py::module_::import("sys").attr("stderr");
    err.attr("write")(line + "\n");
    err.attr("flush")();
  };
  return options;
}

void BindWorkEstimate(py::module_& m) {
  py::register_exception<WorkBoundError>(m, "WorkBoundError", PyExc_ValueError).attr("__doc__") =
      "A run estimated longer than its max_minutes (ccma.workspace, ccma.design): the message gives the "
      "estimate and the max_minutes that would allow it (docs/security.md, \"Work bounded by its cost\").";
  py::class_<WorkEstimate>(m, "_WorkEstimate",
                           "Internal: a run's time estimate and bound (analyses/work_estimate.h), lines on "
                           "sys.stderr.")
      .def(py::init([](const std::string& function, const std::string& noun, long long total, double max_minutes,
                       bool up_to) {
             WorkEstimateOptions options = PythonWorkEstimate(function, noun, max_minutes);
             options.up_to = up_to;
             return std::make_unique<WorkEstimate>(options, total);
           }),
           py::arg("function"), py::arg("noun"), py::arg("total"), py::arg("max_minutes"), py::arg("up_to") = false)
      // The GIL released: a line said from another thread takes it.
      .def("update", &WorkEstimate::Update, py::arg("done"), py::call_guard<py::gil_scoped_release>(),
           "`done` units finished; raises ccma.WorkBoundError beyond the bound.")
      .def("add_later_seconds", &WorkEstimate::AddLaterSeconds, py::arg("seconds"), py::arg("what"),
           py::call_guard<py::gil_scoped_release>(), "Seconds of work known to follow the units.")
      .def("begin_stage", &WorkEstimate::BeginStage, py::arg("noun"), py::arg("total"), py::arg("later_seconds"),
           py::arg("may_refuse"), py::call_guard<py::gil_scoped_release>(),
           "A new stage whose units cost differently.")
      .def_property_readonly("estimated_seconds", &WorkEstimate::estimated_seconds,
                             "The last estimate of the whole run [s]; 0 before the first.");
}

}  // namespace ccma::python
