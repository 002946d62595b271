#include "formats/obstacles_file.h"

#include <set>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/internal/magnitude_checks.h"
#include "formats/internal/obstacle_parser.h"
#include "formats/internal/yaml_checks.h"
#include "formats/internal/yaml_document.h"
#include "formats/model_loader.h"

namespace ccma {

void AddObstaclesFromFile(const std::string& path, Model* model, std::vector<std::string>* warnings) {
  std::string text, error;
  if (!internal::ReadRegularFile(path, kMaxObstacleFileBytes, "obstacles file", &text, &error)) {
    throw ModelError(error);
  }
  AddObstaclesFromString(text, path, model, warnings);
}

void AddObstaclesFromString(const std::string& text, const std::string& path, Model* model,
                            std::vector<std::string>* warnings) {
  if (text.size() > kMaxObstacleFileBytes) {
    throw ModelError(path + ": " + std::to_string(text.size()) + " bytes, more than the " +
                     std::to_string(kMaxObstacleFileBytes) + " an obstacles file may have");
  }
  const YAML::Node root = internal::ParseYamlText(text, path);
  internal::MagnitudeChecks magnitudes(path);
  const internal::YamlReader r(path, warnings, &magnitudes);
  try {
    if (!root.IsMap()) r.Fail(root, "", "an obstacles file must be a mapping with one key, obstacles:");
    r.CheckKeys(root, {"obstacles"}, "");
    std::set<std::string> taken{"world"};
    for (const Body& body : model->bodies) taken.insert(body.name);
    for (const Obstacle& o : model->collision.obstacles) taken.insert(o.name);
    std::vector<Obstacle> obstacles = model->collision.obstacles;
    internal::ParseObstacles(r, r.Require(root, "obstacles", ""), "obstacles", &taken, &obstacles);
    // The model's bases would overlap at home with the default radius.
    if (!model->collision.base_radius_unfit.empty())
      throw ModelError(model->collision.base_radius_unfit);
    model->collision.obstacles = std::move(obstacles);
    model->collision.enabled = true;
  } catch (const YAML::Exception& e) {
    throw ModelError(internal::WithLine(path, e.mark) + ": " + e.msg);
  }
  if (warnings == nullptr) return;
  magnitudes.AppendWarnings(warnings);
  if (model->num_bases() == 0 && model->collision.links.empty()) {
    warnings->push_back(
        path + ": model " + Quote(model->name) +
        " has no mobile bases and no collision.links: none of its bodies is checked against the "
        "obstacles");
  }
}

}  // namespace ccma
