// ccma.generate: `ccma generate` from Python (documents/generate_document.h
// builds the model and its document for both).
#include <pybind11/stl.h>

#include "documents/generate_document.h"
#include "python/src/bindings.h"
#include "python/src/json_to_python.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

// (Model, model file text, the command's JSON without "out").
py::tuple Generate(const std::string& kind, int agents) {
  documents::GenerateSettings settings;
  settings.kind = kind;
  settings.agents = agents;
  if (std::string why; !settings.IsValid(&why)) throw py::value_error("generate: " + why);
  const documents::Generated generated = documents::GenerateModel(settings, "<generated>");
  return py::make_tuple(generated.model, generated.text, ToPython(generated.document.json));
}

}  // namespace

void BindGenerate(py::module_& m) {
  m.def("_generate", &Generate, py::arg("kind"), py::arg("agents"),
        "Private: ccma.generate. The generated model of `kind` (ccma, stewart_gough, legged) with `agents` bases, "
        "legs or quadrupeds, as `ccma generate`: (Model, model file text, the command's JSON without out). "
        "Raises ValueError for settings the command refuses (naming the flag).");
}

}  // namespace ccma::python
