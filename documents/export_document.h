// The files and the document of `ccma export` (docs/cli.md) and of Python's
// export(): a model as URDF with a closure file beside it
// (formats/urdf_writer.h) or as SDFormat with its loops
// (formats/sdformat_writer.h).
#ifndef CCMA_DOCUMENTS_EXPORT_DOCUMENT_H_
#define CCMA_DOCUMENTS_EXPORT_DOCUMENT_H_

#include <string>
#include <vector>

#include "ccma/model.h"
#include "documents/document.h"

namespace ccma::documents {

struct ExportedFile {
  std::string path;
  std::string text;
  // A name ccma derived from the one it was given (the closure file): an
  // entry planted there is replaced, never written through.
  bool derived = false;
};

struct Export {
  // The file named `out` first, then the closure file (URDF). Written last
  // to first: the closure file is in place before the URDF that needs it.
  std::vector<ExportedFile> files;
  Document document;  // {format, closures (path or null), links, joints, loops}, without "out"
};

// `model` written as `format` ("urdf" or "sdf") to be saved at `out`.
// Throws std::invalid_argument for another format.
Export ExportModel(const Model& model, const std::string& format, const std::string& out);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_EXPORT_DOCUMENT_H_
