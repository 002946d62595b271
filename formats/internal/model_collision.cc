// `collision` and `obstacles` (model_format.md, "Collision geometry and
// obstacles"): the margin, the bases' cylinders, capsules fixed in bodies,
// pairs never checked, and the obstacles. Read after the bodies, bases and
// joints, whose names they use.
#include <algorithm>
#include <set>
#include <string>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/internal/base_radius_fit.h"
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
  bool radius_given = false;
  if (YamlReader::Has(root, "collision")) {
    const YAML::Node map = r_.Map(root["collision"], "collision");
    r_.CheckKeys(map, {"margin", "base_radius", "base_height", "links", "ignore"}, "collision");
    if (YamlReader::Has(map, "margin")) geometry.margin = NonNegative(r_, map, "margin", "collision", true);
    radius_given = YamlReader::Has(map, "base_radius");
    if (radius_given)
      geometry.base_radius = NonNegative(r_, map, "base_radius", "collision", false);
    if (YamlReader::Has(map, "base_height")) {
      geometry.base_height = NonNegative(r_, map, "base_height", "collision", false);
    }
    if (YamlReader::Has(map, "links")) ParseCollisionLinks(map["links"], "collision.links");
  }
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
  if (!radius_given) FitDefaultBaseRadius(root);
  for (double given : base_radius_given_)
    geometry.base_radii.push_back(given > 0 ? given : geometry.base_radius);
}

// Without collision.base_radius, bases that give no `radius:` get the
// largest radius up to 0.3 m that leaves every two checked bases twice the
// margin (at least 0.04 m) apart at home: the contract's 0.3 m would make
// bases that stand close together overlap before they move.
void ModelParser::FitDefaultBaseRadius(const YAML::Node& root) {
  CollisionGeometry& geometry = model_.collision;
  const double gap = 2.0 * std::max(geometry.margin, kDefaultMargin);
  const BaseRadiusFit fit = internal::FitDefaultBaseRadius(
      model_, base_radius_given_, geometry.ignore, gap, geometry.base_radius);
  if (fit.radius > 0) {
    geometry.base_radius = fit.radius;
    return;
  }
  const std::string why =
      "not given, and no default fits: bases " +
      Quote(model_.mobile_bases[static_cast<size_t>(fit.a)].name) + " and " +
      Quote(model_.mobile_bases[static_cast<size_t>(fit.b)].name) + " stand " +
      FormatG(fit.distance) + " m apart at home, which leaves no room for the " + FormatG(gap) +
      " m a default radius keeps between bases (twice the margin, at least 0.04 m); set "
      "collision.base_radius, or a radius: on each base";
  if (geometry.enabled)
    r_.Fail(YamlReader::Has(root, "collision") ? root["collision"] : root["obstacles"],
            "collision.base_radius", why);
  geometry.base_radius_unfit = model_.source + ": collision.base_radius: " + why;
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
