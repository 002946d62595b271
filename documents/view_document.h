// The document of `ccma view` (docs/cli.md) and of Python's view() and
// view_html() results: what the page holds (frames, where they came from,
// meshes, loads, the loaded shape, the workspace cloud) and which frames it
// marks; the page itself is viewer/'s.
#ifndef CCMA_DOCUMENTS_VIEW_DOCUMENT_H_
#define CCMA_DOCUMENTS_VIEW_DOCUMENT_H_

#include <cstddef>
#include <string>

#include "ccma/model.h"
#include "documents/document.h"
#include "viewer/mesh_files.h"
#include "viewer/scene.h"

namespace ccma::documents {

// A page of `bytes` bytes drawn from `source` ("model", "trajectory",
// "replay", "controls" or "workspace") with `summary` (viewer::BuildScene);
// `meshes` the mesh files drawn (null: none asked for), `workspace` whether a
// workspace cloud was drawn, `loads` whether the links are coloured by load.
// The document without "out". Document::warnings: frames not assembled or
// reached by a branch jump, frames beyond the work bound, frames below the
// clearance margin, frames with unbalanced or indeterminate loads, a loaded
// shape that is not an equilibrium.
Document ViewDocument(const Model& model, const viewer::SceneSummary& summary, std::size_t bytes,
                      const std::string& source, const viewer::MeshFiles* meshes, bool workspace, bool loads);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_VIEW_DOCUMENT_H_
