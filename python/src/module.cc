// PYBIND11_MODULE for `ccma._ccma`; the package `ccma` (python/ccma/__init__.py)
// re-exports it and adds the pure-Python parts (view in Jupyter).
#include "python/src/bindings.h"

PYBIND11_MODULE(_ccma, m) {
  m.doc() =
      "ccma: simulation and kinematic control of closed-loop mechanisms driven by mobile "
      "robots (Constrained Collaborative Mobile Agents). Units: metres, radians, seconds.";
  m.attr("__version__") = CCMA_VERSION;
  ccma::python::BindModel(m);
  ccma::python::BindForward(m);
  ccma::python::BindControl(m);
  ccma::python::BindAnalysis(m);
  ccma::python::BindReplay(m);
  ccma::python::BindView(m);
  ccma::python::BindWorkEstimate(m);
  ccma::python::BindDesign(m);
  ccma::python::BindWorkspace(m);
  ccma::python::BindImport(m);
  ccma::python::BindGenerate(m);
  ccma::python::BindCollision(m);
  ccma::python::BindStatics(m);
  ccma::python::BindDynamics(m);
}
