// `mobile_bases[k].wheels`: the list of omni wheels of an omni base, or the
// axle (`track`, `radius`) of a differential base.
#include <stdexcept>
#include <string>

#include "ccma/limits.h"
#include "ccma/omni_wheels.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

DifferentialWheels ModelParser::ParseDifferentialWheels(const YAML::Node& node,
                                                        const std::string& path) const {
  const YAML::Node map = r_.Map(node, path);
  r_.CheckKeys(map, {"track", "radius"}, path);
  DifferentialWheels wheels;
  wheels.track = r_.Number(r_.Require(map, "track", path), path + ".track", "m");
  wheels.radius = r_.Number(r_.Require(map, "radius", path), path + ".radius", "m");
  if (!(wheels.track > 0)) r_.Fail(map["track"], path + ".track", "must be positive (m)");
  if (!(wheels.radius > 0)) r_.Fail(map["radius"], path + ".radius", "must be positive (m)");
  return wheels;
}

std::vector<Wheel> ModelParser::ParseWheels(const YAML::Node& node, const std::string& path) const {
  const YAML::Node wheels = r_.Sequence(node, path, static_cast<std::size_t>(kMaxWheels), "wheels");
  std::vector<Wheel> result;
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    const std::string wpath = Indexed(path, i);
    const YAML::Node w = r_.Map(wheels[i], wpath);
    r_.CheckKeys(w, {"angle", "distance", "radius", "mounting", "roller"}, wpath);
    Wheel wheel;
    wheel.angle = r_.Number(r_.Require(w, "angle", wpath), wpath + ".angle", "rad");
    wheel.distance = r_.Number(r_.Require(w, "distance", wpath), wpath + ".distance", "m");
    wheel.radius = r_.Number(r_.Require(w, "radius", wpath), wpath + ".radius", "m");
    if (w["mounting"].IsDefined()) {
      wheel.mounting = r_.Number(w["mounting"], wpath + ".mounting", "rad");
    }
    if (w["roller"].IsDefined()) wheel.roller = r_.Number(w["roller"], wpath + ".roller", "rad");
    result.push_back(wheel);
  }
  try {
    OmniWheelKinematics check(result);
  } catch (const std::invalid_argument& e) {
    r_.Fail(wheels, path, e.what());
  }
  return result;
}

}  // namespace internal
}  // namespace ccma
