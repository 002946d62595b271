// The Python module `ccma` (pybind11): one Bind* function per concept, all
// called from module.cc. Conventions shared by every file here:
//  * NumPy in and out through pybind11/eigen.h: inputs are taken as
//    Eigen::Ref<const ...> (no copy for a contiguous float64 array), results
//    are returned by value and moved into NumPy (no second copy);
//  * units as in the C++ headers (m, rad, s, m^2), written in each docstring;
//  * solves release the GIL (py::call_guard<py::gil_scoped_release>): other
//    Python threads run meanwhile, but one problem object must be used by
//    one thread at a time (like the C++ objects);
//  * problems keep the Model alive (py::keep_alive), since the C++ problems
//    hold a reference to it.
#ifndef CCMA_PYTHON_SRC_BINDINGS_H_
#define CCMA_PYTHON_SRC_BINDINGS_H_

#include <pybind11/pybind11.h>

namespace ccma::python {

void BindModel(pybind11::module_& m);      // load_model, Model and its parts, ModelError
void BindForward(pybind11::module_& m);    // ForwardOptions, ForwardProblem, results, poses
void BindControl(pybind11::module_& m);    // ControlOptions, ControlProblem, paths, sensitivities
void BindAnalysis(pybind11::module_& m);   // mobility
void BindReplay(pybind11::module_& m);     // waypoints and the simulated closed loop
void BindGenerate(pybind11::module_& m);   // generated model files (private; ccma.generate wraps it)
void BindView(pybind11::module_& m);       // the 3D viewer's HTML
void BindWorkspace(pybind11::module_& m);  // workspace maps (private; ccma.workspace wraps them)
void BindDesign(pybind11::module_& m);     // design parameters: ds/dp and the design loop
void BindImport(pybind11::module_& m);     // robots described elsewhere (URDF, SDFormat)
void BindCollision(pybind11::module_& m);  // clearance, whole-trajectory planning
void BindStatics(pybind11::module_& m);    // joint reactions and control efforts
void BindDynamics(pybind11::module_& m);   // inverse dynamics and retiming along a trajectory
void BindWorkEstimate(pybind11::module_& m);  // WorkBoundError, the bound on a run's estimated time

}  // namespace ccma::python

#endif  // CCMA_PYTHON_SRC_BINDINGS_H_
