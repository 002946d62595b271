#include "formats/internal/sdformat_world.h"

#include <cmath>
#include <optional>
#include <sdf/Element.hh>
#include <sdf/Link.hh>
#include <sdf/World.hh>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/model_loader.h"
#include "formats/robot_description.h"

namespace ccma::internal {

// SDFormat 1.11's <inertial auto="true"> (computed from the collisions'
// density) needs libsdformat 14; Debian's reads it as the default inertial.
void WarnOfComputedInertials(const TiXmlElement& e, const std::string& source, std::vector<std::string>* warnings) {
  for (const TiXmlElement* c = e.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
    const char* automatic = c->Attribute("auto");
    if (std::string(c->Value()) == "inertial" && automatic != nullptr && std::string(automatic) == "true") {
      warnings->push_back(source + ":" + std::to_string(c->Row()) + ": <inertial auto=\"true\">: computing it from the "
                          "collisions needs libsdformat 14; this libsdformat reads it as SDFormat's default, 1 kg, "
                          "inertia diag(1, 1, 1) kg m^2 at the link's origin");
    }
    WarnOfComputedInertials(*c, source, warnings);
  }
}

namespace {

// "N link(s) WHAT ('a', 'b', ... and k more) THEN" for the links of `model`
// whose element `picked` says yes; "" for none.
std::string LinksSentence(const sdf::Model& model, bool (*picked)(const sdf::ElementPtr&), const std::string& what,
                          const std::string& then) {
  std::string names;
  int count = 0;
  for (uint64_t i = 0; i < model.LinkCount(); ++i) {
    const sdf::Link& link = *model.LinkByIndex(i);
    if (!picked(link.Element())) continue;
    if (++count <= 5) names += (names.empty() ? "" : ", ") + Quote(link.Name());
  }
  if (count == 0) return "";
  if (count > 5) names += " and " + std::to_string(count - 5) + " more";
  return std::to_string(count) + " link(s) " + what + " (" + names + ")" + then;
}

}  // namespace

// SDFormat gives a link without <inertial> 1 kg and a unit inertia, as
// Gazebo simulates it; the import takes that too, and names those links.
void AddDefaultInertialsWarning(const sdf::Model& model, const std::string& source, RobotDescription* robot) {
  const std::string sentence = LinksSentence(
      model, [](const sdf::ElementPtr& e) { return e == nullptr || !e->HasElement("inertial"); }, "without <inertial>",
      " get SDFormat's default, as Gazebo simulates them: 1 kg, inertia diag(1, 1, 1) kg m^2 at the link's origin");
  if (!sentence.empty()) robot->warnings.push_back(source + ": " + sentence);
}

// A link's <gravity>false</gravity> (gravity does not act on it in Gazebo):
// ccma weighs every mass, and says which links the file exempts.
void AddWeightlessLinksWarning(const sdf::Model& model, const std::string& source, RobotDescription* robot) {
  const std::string sentence = LinksSentence(
      model, [](const sdf::ElementPtr& e) { return e != nullptr && e->HasElement("gravity") && !e->Get<bool>("gravity"); },
      "with <gravity>false</gravity>",
      ": ccma applies gravity to every mass, so statics weighs them too (remove their mass from the model file to "
      "leave them weightless)");
  if (!sentence.empty()) robot->warnings.push_back(source + ": " + sentence);
}

// A world's gravity (its <gravity>, 1.4's <physics><gravity> converted to
// it, or SDFormat's default for a world, (0, 0, -9.8) m/s^2, as Gazebo
// simulates it): the robot's gravity. A file of one <model> keeps ccma's.
void ReadWorldGravity(const sdf::Root& root, const std::string& source, RobotDescription* robot) {
  if (root.Model() != nullptr || root.WorldCount() != 1) return;
  const sdf::World& world = *root.WorldByIndex(0);
  const ignition::math::Vector3d g = world.Gravity();
  const Eigen::Vector3d gravity(g.X(), g.Y(), g.Z());
  if (!gravity.allFinite() || gravity.norm() > 1e3) {
    throw ModelError(source + ": <world><gravity>: three finite numbers of at most 1000 m/s^2 are needed");
  }
  robot->has_gravity = true;
  robot->gravity = gravity;
}

// The file's one <model>, or the one model of its one <world> that is not
// static (a world's ground plane is a static model: skipped, with a warning).
const sdf::Model& TheModel(const sdf::Root& root, const std::string& source, std::vector<std::string>* warnings) {
  const sdf::Model* model = root.Model();
  if (model == nullptr && root.WorldCount() == 1) {
    const sdf::World& world = *root.WorldByIndex(0);
    std::vector<const sdf::Model*> moving;
    std::string skipped;
    for (uint64_t i = 0; i < world.ModelCount(); ++i) {
      const sdf::Model* m = world.ModelByIndex(i);
      if (m->Static()) {
        skipped += (skipped.empty() ? "" : ", ") + Quote(m->Name());
      } else {
        moving.push_back(m);
      }
    }
    if (moving.size() == 1) {
      model = moving.front();
      if (!skipped.empty()) warnings->push_back(source + ": static model(s) " + skipped + " of the world skipped");
    } else if (moving.size() > 1) {
      std::string names;
      for (const sdf::Model* m : moving) names += (names.empty() ? "" : ", ") + Quote(m->Name());
      throw ModelError(source + ": the world holds " + std::to_string(moving.size()) + " models that are not static (" +
                       names + "): ccma imports one robot; put it in a file of its own");
    }
  }
  if (model == nullptr)
    throw ModelError(source + ": the file must hold one <model> (or one <world> with one model that is not static)");
  if (model->ModelCount() > 0) {
    const sdf::ElementPtr nested = model->ModelByIndex(0)->Element();
    const std::optional<int> line = nested ? nested->LineNumber() : std::nullopt;
    throw ModelError(source + (line ? ":" + std::to_string(*line) : std::string()) +
                     ": model " + Quote(model->ModelByIndex(0)->Name()) +
                     ": nested models are not supported");
  }
  if (model->LinkCount() > static_cast<uint64_t>(kMaxRobotLinks) ||
      model->JointCount() > static_cast<uint64_t>(kMaxRobotJoints)) {
    throw ModelError(source + ": " + std::to_string(model->LinkCount()) + " links and " +
                     std::to_string(model->JointCount()) + " joints: ccma imports at most " +
                     std::to_string(kMaxRobotLinks) + " links and " + std::to_string(kMaxRobotJoints) + " joints");
  }
  return *model;
}

}  // namespace ccma::internal
