// The document of `ccma import` (docs/cli.md, docs/import.md) and of
// Python's import_robot() result: what the imported model holds (bodies,
// joints, loops, actuated joints, controlled components, collision
// capsules) and its home assembly.
#ifndef CCMA_DOCUMENTS_IMPORT_DOCUMENT_H_
#define CCMA_DOCUMENTS_IMPORT_DOCUMENT_H_

#include "analyses/robot_import.h"
#include "documents/document.h"

namespace ccma::documents {

// The robot as ImportRobot made it with `options`. The document without
// "out". Document::warnings: the import's (ImportedRobot::warnings); the
// reader's (RobotDescription::warnings) are said as the file is read, before
// an import that may fail.
Document ImportDocument(const ImportedRobot& imported, const ImportOptions& options);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_IMPORT_DOCUMENT_H_
