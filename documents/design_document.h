// The document of `ccma design` (docs/cli.md) and of Python's design(): which
// targets the designed model reaches with margin (before and after), what
// changed (each varied number and each moved joint point), and the
// objective's value before and after its phase.
#ifndef CCMA_DOCUMENTS_DESIGN_DOCUMENT_H_
#define CCMA_DOCUMENTS_DESIGN_DOCUMENT_H_

#include <vector>

#include "analyses/design.h"
#include "ccma/ccma.h"
#include "documents/document.h"

namespace ccma::documents {

// `model` as loaded, `designed` with the result's parameters applied,
// `final_check` the targets evaluated in the model as written (loaded back
// from the patched text). The document without "out". Document::warnings:
// "not converged: ..." when a target is missed or below the margin, or the
// objective's "not defined" note.
Document DesignDocument(const Model& model, const Model& designed, const DesignParameters& params,
                        const DesignOptions& options, const DesignResult& result,
                        const std::vector<DesignTargetResult>& final_check);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_DESIGN_DOCUMENT_H_
