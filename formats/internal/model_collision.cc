// `collision` and `obstacles` (model_format.md, "Collision geometry and
// obstacles"): the margin, the bases' cylinders, capsules fixed in bodies,
// pairs never checked, and the obstacles. Read after the bodies, bases and
// joints, whose names they use.
#include <set>
#include <string>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/internal/model_parser.h"
#include "formats/internal/obstacle_parser.h"

namespace ccma {
namespace internal {
namespace {

double NonNegative(const YamlReader& r, const YAML::Node& map, const std::string& key, const std::string& path,
                   bool zero_allowed) {
  const YAML::Node node = map[key];
  const double value = r.Number(node, YamlReader::Join(path, key), "m");
  if (!(value > 0 || (zero_allowed && value == 0))) {
    r.Fail(node, YamlReader::Join(path, key),
           std::string(zero_allowed ? "must not be negative" : "must be positive") + " (m), got " + FormatG(value));
  }
  return value;
}

}  // namespace

// A base's own `radius:` [m], or 0 when it gives none.
double ModelParser::BaseRadius(const YAML::Node& base, const std::string& path) const {
  if (!YamlReader::Has(base, "radius")) return 0.0;
  return NonNegative(r_, base, "radius", path, /*zero_allowed=*/false);
}

void ModelParser::ParseCollision(const YAML::Node& root) {
  CollisionGeometry& geometry = model_.collision;
  geometry.enabled = YamlReader::Has(root, "collision") || YamlReader::Has(root, "obstacles");
  if (YamlReader::Has(root, "collision")) {
    const YAML::Node map = r_.Map(root["collision"], "collision");
    r_.CheckKeys(map, {"margin", "base_radius", "base_height", "links", "ignore"}, "collision");
    if (YamlReader::Has(map, "margin")) geometry.margin = NonNegative(r_, map, "margin", "collision", true);
    if (YamlReader::Has(map, "base_radius")) {
      geometry.base_radius = NonNegative(r_, map, "base_radius", "collision", false);
    }
    if (YamlReader::Has(map, "base_height")) {
      geometry.base_height = NonNegative(r_, map, "base_height", "collision", false);
    }
    if (YamlReader::Has(map, "links")) ParseCollisionLinks(map["links"], "collision.links");
  }
  for (double given : base_radius_given_) geometry.base_radii.push_back(given > 0 ? given : geometry.base_radius);
  if (YamlReader::Has(root, "obstacles")) {
    std::set<std::string> taken;
    for (const Body& body : model_.bodies) taken.insert(body.name);
    taken.insert("world");
    ParseObstacles(r_, root["obstacles"], "obstacles", &taken, &geometry.obstacles);
  }
  // Pairs name obstacles too: read last.
  if (YamlReader::Has(root, "collision") && YamlReader::Has(root["collision"], "ignore")) {
    ParseIgnoredPairs(root["collision"]["ignore"], "collision.ignore");
  }
}

void ModelParser::ParseCollisionLinks(const YAML::Node& node, const std::string& path) {
  const YAML::Node links = r_.Sequence(node, path, static_cast<std::size_t>(kMaxCollisionLinks), "links");
  for (std::size_t i = 0; i < links.size(); ++i) {
    const std::string at = Indexed(path, i);
    const YAML::Node link = r_.Map(links[i], at);
    r_.CheckKeys(link, {"body", "from", "to", "radius"}, at);
    CollisionCapsule capsule;
    capsule.body = BodyAt(r_.Require(link, "body", at), at + ".body");
    capsule.line = link.Mark().line + 1;
    const Body& body = model_.bodies[capsule.body];
    // Ends are given in world coordinates at home; stored in the body frame.
    const Eigen::Vector3d from = r_.Vector3(r_.Require(link, "from", at), at + ".from", "m");
    const Eigen::Vector3d to = r_.Vector3(r_.Require(link, "to", at), at + ".to", "m");
    capsule.a_B = body.R_WB_home.transpose() * (from - body.p_WB_home);
    capsule.b_B = body.R_WB_home.transpose() * (to - body.p_WB_home);
    r_.Require(link, "radius", at);
    capsule.radius = NonNegative(r_, link, "radius", at, false);
    model_.collision.links.push_back(capsule);
  }
}

void ModelParser::ParseIgnoredPairs(const YAML::Node& node, const std::string& path) {
  const YAML::Node pairs = r_.Sequence(node, path, static_cast<std::size_t>(kMaxIgnoredPairs), "pairs");
  std::set<std::string> names;
  for (const Body& body : model_.bodies) names.insert(body.name);
  for (const Obstacle& o : model_.collision.obstacles) names.insert(o.name);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const std::string at = Indexed(path, i);
    const YAML::Node pair = pairs[i];
    if (!pair.IsSequence() || pair.size() != 2) r_.Fail(pair, at, "must be a pair of names [a, b]");
    std::string both[2];
    for (std::size_t k = 0; k < 2; ++k) {
      both[k] = r_.String(pair[k], Indexed(at, k));
      if (names.count(both[k]) == 0) {
        r_.Fail(pair[k], Indexed(at, k), "unknown body, base or obstacle " + Quote(both[k]));
      }
    }
    model_.collision.ignore.emplace_back(both[0], both[1]);
  }
}

}  // namespace internal
}  // namespace ccma
