// The document of `ccma replay` (docs/cli.md) and of Python's replay(): how
// the simulated closed loop went (converged, torn, trustworthy), the
// imperfections and gains it ran with, the RMSE per reported component and,
// for the paper's models, the paper's hardware rows. The files it writes are
// documents/replay_report.h's.
#ifndef CCMA_DOCUMENTS_REPLAY_DOCUMENT_H_
#define CCMA_DOCUMENTS_REPLAY_DOCUMENT_H_

#include "ccma/model.h"
#include "documents/document.h"
#include "execution/replay.h"

namespace ccma::documents {

// The document without "files", "plots" and "plot_warning" (the CLI's own).
// Document::warnings: one per way the replay failed (ReplayFailures), which
// the JSON's "warning" joins.
Document ReplayDocument(const Model& model, const ReplayOptions& options, const ReplayResult& result);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_REPLAY_DOCUMENT_H_
