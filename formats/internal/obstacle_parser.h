// The `obstacles:` list (model_format.md, "Collision geometry and
// obstacles"), shared by the model loader and --obstacles files
// (formats/obstacles_file.h): vertical cylinders on the floor and boxes
// turned about z, each named.
//
// Internal to the library.
#ifndef CCMA_FORMATS_INTERNAL_OBSTACLE_PARSER_H_
#define CCMA_FORMATS_INTERNAL_OBSTACLE_PARSER_H_

#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "ccma/collision_geometry.h"
#include "formats/internal/yaml_checks.h"

namespace ccma {
namespace internal {

// Appends the obstacles of the list `node` (key path `path`) to `obstacles`.
// `taken` holds the names already in use (bodies, bases, obstacles); each
// new name is added to it. A missing name becomes "obstacle<i>" (i: index in
// all obstacles). Throws ModelError "file:line: key: what" for a malformed
// entry, a name in use, or more than kMaxObstacles in all.
void ParseObstacles(const YamlReader& r, const YAML::Node& node, const std::string& path,
                    std::set<std::string>* taken, std::vector<Obstacle>* obstacles);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_OBSTACLE_PARSER_H_
