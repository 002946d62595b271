// `meshes` of bodies and mobile bases: visual meshes fixed in the body, for
// `ccma view --meshes`. Poses are written in world coordinates at home, like
// everything else in the format, and stored relative to the body's frame.
// The loader never opens the mesh files: only the viewer reads them.
#include <string>
#include <vector>

#include "ccma/limits.h"
#include "ccma/rotation.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

// The list at `node` (path "bodies[i].meshes"), for `body`, whose home pose
// is already known. Counts toward kMaxMeshes in the whole model.
std::vector<BodyMesh> ModelParser::ParseMeshes(const YAML::Node& node, const std::string& path, const Body& body) {
  const YAML::Node list = r_.Sequence(node, path, kMaxMeshesPerBody, "meshes");
  num_meshes_ += list.size();
  if (num_meshes_ > static_cast<std::size_t>(kMaxMeshes)) {
    r_.Fail(list, path, "more than " + std::to_string(kMaxMeshes) + " meshes in the model");
  }
  std::vector<BodyMesh> meshes;
  for (std::size_t i = 0; i < list.size(); ++i) meshes.push_back(ParseMesh(list[i], Indexed(path, i), body));
  return meshes;
}

// One entry: {file, position, rpy, scale}. The mesh frame M at home is
// (R_WM, p_WM); stored as R_BM = R_WB^T R_WM, p_BM = R_WB^T (p_WM - p_WB).
BodyMesh ModelParser::ParseMesh(const YAML::Node& at, const std::string& path, const Body& body) const {
  const YAML::Node node = r_.Map(at, path);
  r_.CheckKeys(node, {"file", "position", "rpy", "scale"}, path);
  BodyMesh mesh;
  mesh.line = node.Mark().line + 1;
  const YAML::Node file = r_.Require(node, "file", path);
  mesh.file = r_.String(file, path + ".file");
  if (mesh.file.size() > kMaxMeshPathLength) {
    r_.Fail(file, path + ".file", "longer than " + std::to_string(kMaxMeshPathLength) + " bytes");
  }
  if (mesh.file.find('\0') != std::string::npos) r_.Fail(file, path + ".file", "contains a NUL character");
  Eigen::Vector3d p_WM = body.p_WB_home;
  Eigen::Matrix3d R_WM = body.R_WB_home;
  if (YamlReader::Has(node, "position")) p_WM = r_.Vector3(node["position"], path + ".position", "m");
  if (YamlReader::Has(node, "rpy")) R_WM = RotationFromRpy(r_.Vector3(node["rpy"], path + ".rpy", "rad"));
  mesh.R_BM = body.R_WB_home.transpose() * R_WM;
  mesh.p_BM = body.R_WB_home.transpose() * (p_WM - body.p_WB_home);
  if (YamlReader::Has(node, "scale")) {
    mesh.scale = r_.Vector3(node["scale"], path + ".scale", "unitless");
    for (int k = 0; k < 3; ++k) {
      if (!(mesh.scale[k] > 0)) r_.Fail(node["scale"][k], Indexed(path + ".scale", k), "must be positive");
    }
  }
  return mesh;
}

}  // namespace internal
}  // namespace ccma
