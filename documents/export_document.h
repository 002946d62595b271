// The files and the document of `ccma export` (docs/cli.md) and of Python's
// export(): a model as URDF with a closure file beside it
// (formats/urdf_writer.h), as SDFormat with its loops
// (formats/sdformat_writer.h) or as MuJoCo MJCF with its loops as equality
// constraints (formats/mjcf_writer.h).
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
  // {format, closures (path or null), links, joints, loops}, without "out";
  // MJCF: {format, closures: null, bodies, joints, equalities, actuators, loops}.
  Document document;
};

// Whether `format` is one ExportModel writes: "urdf", "sdf" or "mjcf".
bool IsExportFormat(const std::string& format);
// What the formats are, for messages: "urdf, sdf or mjcf".
constexpr const char* kExportFormats = "urdf, sdf or mjcf";

// `model` written as `format` to be saved at `out`. Throws
// std::invalid_argument for another format, or a model the format cannot
// hold (MJCF: a loop only a prismatic or universal joint can cut).
Export ExportModel(const Model& model, const std::string& format, const std::string& out);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_EXPORT_DOCUMENT_H_
