#include "documents/export_document.h"

#include <stdexcept>

#include "formats/mjcf_writer.h"
#include "formats/sdformat_writer.h"
#include "formats/urdf_writer.h"

namespace ccma::documents {

bool IsExportFormat(const std::string& format) { return format == "urdf" || format == "sdf" || format == "mjcf"; }

Export ExportModel(const Model& model, const std::string& format, const std::string& out) {
  Export e;
  nlohmann::json& json = e.document.json;
  json = {{"format", format}, {"closures", nullptr}};
  if (format == "urdf") {
    UrdfExport urdf = WriteUrdf(model);
    const std::string closures = ClosureFilePath(out);
    e.files.push_back({out, std::move(urdf.urdf), false});
    e.files.push_back({closures, std::move(urdf.closures), true});
    json["closures"] = closures;
    json["links"] = urdf.links;
    json["joints"] = urdf.joints;
    json["loops"] = urdf.loops;
  } else if (format == "sdf") {
    SdformatExport sdf = WriteSdformat(model);
    e.files.push_back({out, std::move(sdf.sdf), false});
    json["links"] = sdf.links;
    json["joints"] = sdf.joints;
    json["loops"] = sdf.loops;
  } else if (format == "mjcf") {
    MjcfExport mjcf = WriteMjcf(model);
    e.files.push_back({out, std::move(mjcf.mjcf), false});
    json["bodies"] = mjcf.bodies;
    json["joints"] = mjcf.joints;
    json["equalities"] = mjcf.equalities;
    json["actuators"] = mjcf.actuators;
    json["loops"] = mjcf.loops;
  } else {
    throw std::invalid_argument(std::string("format must be ") + kExportFormats);
  }
  return e;
}

}  // namespace ccma::documents
