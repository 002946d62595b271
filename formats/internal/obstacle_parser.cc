#include "formats/internal/obstacle_parser.h"

#include <algorithm>
#include <cmath>

#include "ccma/internal/format.h"
#include "ccma/limits.h"

namespace ccma {
namespace internal {
namespace {

double Positive(const YamlReader& r, const YAML::Node& map, const std::string& key, const std::string& path) {
  const YAML::Node node = r.Require(map, key, path);
  const double value = r.Number(node, YamlReader::Join(path, key), "m");
  if (!(value > 0)) r.Fail(node, YamlReader::Join(path, key), "must be positive (m), got " + FormatG(value));
  return value;
}

// Two or three numbers [m].
Eigen::Vector3d Point(const YamlReader& r, const YAML::Node& node, const std::string& path, std::size_t n) {
  if (!node.IsSequence() || node.size() != n) {
    r.Fail(node, path, "must be a list of " + std::to_string(n) + " numbers (m)");
  }
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) p[static_cast<int>(i)] = r.Number(node[i], Indexed(path, i), "m");
  return p;
}

void ParseCylinder(const YamlReader& r, const YAML::Node& node, const std::string& path, Obstacle* o) {
  const YAML::Node map = r.Map(node, path);
  r.CheckKeys(map, {"center", "radius", "height"}, path);
  o->shape = ObstacleShape::kCylinder;
  o->center = Point(r, r.Require(map, "center", path), path + ".center", 2);
  o->radius = Positive(r, map, "radius", path);
  o->z_min = 0;
  o->z_max = Positive(r, map, "height", path);
}

void ParseBox(const YamlReader& r, const YAML::Node& node, const std::string& path, Obstacle* o) {
  const YAML::Node map = r.Map(node, path);
  r.CheckKeys(map, {"center", "size", "yaw"}, path);
  o->shape = ObstacleShape::kBox;
  o->center = Point(r, r.Require(map, "center", path), path + ".center", 3);
  const YAML::Node size = r.Require(map, "size", path);
  o->size = Point(r, size, path + ".size", 3);
  if (!(o->size.minCoeff() > 0)) r.Fail(size, path + ".size", "every side must be positive (m)");
  o->yaw = YamlReader::Has(map, "yaw") ? r.Number(map["yaw"], path + ".yaw", "rad") : 0.0;
  o->z_min = o->center.z() - 0.5 * o->size.z();
  o->z_max = o->center.z() + 0.5 * o->size.z();
}

Obstacle ParseObstacle(const YamlReader& r, const YAML::Node& at, const std::string& path, std::size_t index,
                       std::set<std::string>* taken) {
  const YAML::Node node = r.Map(at, path);
  r.CheckKeys(node, {"name", "cylinder", "box"}, path);
  Obstacle o;
  o.source = r.source();
  o.line = node.Mark().line + 1;
  const YAML::Node name = node["name"];
  o.name = YamlReader::Has(node, "name") ? r.Name(name, path + ".name") : "obstacle" + std::to_string(index);
  if (!taken->insert(o.name).second) {
    r.Fail(YamlReader::Has(node, "name") ? name : node, path + ".name",
           "the name " + Quote(o.name) + " is already used by a body, base or obstacle");
  }
  const bool cylinder = YamlReader::Has(node, "cylinder"), box = YamlReader::Has(node, "box");
  if (cylinder == box) r.Fail(node, path, "give exactly one of cylinder: or box:");
  if (cylinder) ParseCylinder(r, node["cylinder"], path + ".cylinder", &o);
  if (box) ParseBox(r, node["box"], path + ".box", &o);
  return o;
}

}  // namespace

void ParseObstacles(const YamlReader& r, const YAML::Node& node, const std::string& path,
                    std::set<std::string>* taken, std::vector<Obstacle>* obstacles) {
  const std::size_t room = static_cast<std::size_t>(kMaxObstacles) - std::min(obstacles->size(),
                                                                               static_cast<std::size_t>(kMaxObstacles));
  const YAML::Node list = r.Sequence(node, path, room, "obstacles");
  for (std::size_t i = 0; i < list.size(); ++i) {
    obstacles->push_back(ParseObstacle(r, list[i], Indexed(path, i), obstacles->size(), taken));
  }
}

}  // namespace internal
}  // namespace ccma
