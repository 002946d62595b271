// The document of `ccma check` (docs/cli.md) and Python's `ccma.check`: a
// model's counts and its mobility at home, and what a user would not expect
// of it (a motion left free, not assembled, fewer end-effector DOF than
// controlled components), one sentence each in "warnings".
#ifndef CCMA_DOCUMENTS_CHECK_DOCUMENT_H_
#define CCMA_DOCUMENTS_CHECK_DOCUMENT_H_

#include "ccma/ccma.h"
#include "documents/document.h"

namespace ccma::documents {

// The model analysed at home (AnalyzeMobility). Document::warnings: each of
// "warnings", then the clearance's when below the margin.
Document CheckDocument(const Model& model);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_CHECK_DOCUMENT_H_
