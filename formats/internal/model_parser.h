// The model loader's parser: turns a YAML tree into a Model, one section of
// the format (docs/model_format.md) at a time. Each section lives in its own
// file, so a new key or section is one new function in an obvious place:
//   model_top_level.cc       the top level, name, description; the order of sections
//   model_bodies.cc          bodies, and the names of bodies and bases
//   model_bases.cc           mobile_bases (type, actuation, pose)
//   model_wheels.cc          mobile_bases[k].wheels (omni wheels, differential axle)
//   model_joints.cc          joints (names, type, between); connectivity
//   model_joint_geometry.cc  joints' point, axis, axes
//   model_actuation_limits.cc joints' actuated and limits
//   model_end_effector.cc    end_effector
//   model_meshes.cc          bodies' and bases' meshes (visual only)
//   model_collision.cc       collision (margin, base cylinders, link capsules, ignore) and obstacles
//   model_masses.cc          mass, com, payload, gravity, effort_limits, push_limit
//   model_stiffness.cc       stiffness of bases and joints (compliance)
// Shared checks (keys, numbers, vectors, messages): yaml_checks.h.
//
// Internal to the library: formats/model_loader.h is the public API.
#ifndef CCMA_FORMATS_INTERNAL_MODEL_PARSER_H_
#define CCMA_FORMATS_INTERNAL_MODEL_PARSER_H_

#include <map>
#include <numeric>
#include <string>
#include <unordered_map>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "ccma/model.h"
#include "formats/internal/magnitude_checks.h"
#include "formats/internal/yaml_checks.h"

namespace ccma {
namespace internal {

// Union-find over body indices, to find bodies no joint ties to a base.
// Iterative, with union by size: no recursion however long the chain.
class Components {
 public:
  explicit Components(int n) : parent_(n), size_(n, 1) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int Find(int i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];  // path halving
      i = parent_[i];
    }
    return i;
  }
  void Unite(int a, int b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<int> parent_;
  std::vector<int> size_;
};

// One use per model file: construct, then Parse().
class ModelParser {
 public:
  // `source` names the file in messages; `warnings` (may be null) receives
  // unknown keys and implausible magnitudes.
  ModelParser(const std::string& source, std::vector<std::string>* warnings);

  // The model of the document `root`; throws ModelError on any problem.
  Model Parse(const YAML::Node& root);

 private:
  struct NamedBody {
    int index;
    YAML::Node node;  // where it was declared, for messages
  };

  // model_top_level.cc
  void ParseHeader(const YAML::Node& root);

  // model_bodies.cc
  void ParseBodies(const YAML::Node& bodies);
  std::string AddBodyName(const YAML::Node& node, const std::string& path);
  int BodyOrWorldAt(const YAML::Node& node, const std::string& path) const;
  int BodyAt(const YAML::Node& node, const std::string& path) const;
  std::string NameOf(int body) const;

  // model_bases.cc
  void ParseBases(const YAML::Node& bases_node, std::size_t num_bodies);
  MobileBase ParseBase(const YAML::Node& at, const std::string& path);
  void ParseActuation(const YAML::Node& node, const std::string& path, MobileBase* base) const;
  void CheckTypeKeys(const YAML::Node& node, const std::string& path, BaseType type) const;

  // model_legged.cc
  LeggedBody ParseLeggedBody(const YAML::Node& node, const std::string& path) const;
  ControlRange ParseBodyLimit(const YAML::Node& limits, const std::string& path, const char* key, double home,
                              const char* unit) const;

  // model_wheels.cc
  DifferentialWheels ParseDifferentialWheels(const YAML::Node& node, const std::string& path) const;
  std::vector<Wheel> ParseWheels(const YAML::Node& node, const std::string& path) const;

  // model_joints.cc
  void ParseJoints(const YAML::Node& joints);
  Joint ParseJoint(const YAML::Node& node, const std::string& path);
  // Joint names given in the file: where, and the joint's index.
  using JointNames = std::map<std::string, std::pair<YAML::Node, std::size_t>>;
  void CheckDefaultJointNames(const JointNames& names, const std::vector<bool>& named) const;
  void CheckConnected(const YAML::Node& bodies);

  // model_joint_geometry.cc
  void ParseJointGeometry(const YAML::Node& node, const std::string& path, Joint* joint) const;

  // model_actuation_limits.cc
  void ParseActuationAndLimits(const YAML::Node& node, const std::string& path, Joint* joint) const;

  // model_end_effector.cc
  void ParseEndEffector(const YAML::Node& ee);

  // model_meshes.cc
  std::vector<BodyMesh> ParseMeshes(const YAML::Node& node, const std::string& path, const Body& body);
  BodyMesh ParseMesh(const YAML::Node& at, const std::string& path, const Body& body) const;

  // model_masses.cc
  MassProperties ParseMassProperties(const YAML::Node& node, const std::string& path, const Body& body) const;
  void ParseEffortLimits(const YAML::Node& node, const std::string& path, Joint* joint) const;
  double ParsePushLimit(const YAML::Node& node, const std::string& path) const;

  // model_velocity_limits.cc
  void ParseJointVelocityLimit(const YAML::Node& node, const std::string& path, Joint* joint) const;
  std::vector<double> ParseBaseVelocityLimit(const YAML::Node& node, const std::string& path, BaseType type) const;
  void ParseLoads(const YAML::Node& root, const YAML::Node& end_effector);

  // model_stiffness.cc
  double StiffnessValue(const YAML::Node& node, const std::string& path, const char* unit) const;
  std::vector<double> StiffnessValues(const YAML::Node& node, const std::string& path, int count,
                                      const char* unit) const;
  BaseStiffness ParseBaseStiffness(const YAML::Node& node, const std::string& path) const;
  void ParseJointStiffness(const YAML::Node& node, const std::string& path, Joint* joint) const;

  // model_collision.cc
  void ParseCollision(const YAML::Node& root);
  void ParseCollisionLinks(const YAML::Node& node, const std::string& path);
  void ParseIgnoredPairs(const YAML::Node& node, const std::string& path);
  double BaseRadius(const YAML::Node& base, const std::string& path) const;
  void FitDefaultBaseRadius(const YAML::Node& root);

  MagnitudeChecks magnitudes_;
  std::vector<std::string>* warnings_;
  const YamlReader r_;
  Model model_;
  std::unordered_map<std::string, NamedBody> body_names_;  // bodies and bases
  Components components_{0};
  std::vector<int> grounded_bodies_;  // bodies jointed to `world`
  std::size_t num_meshes_ = 0;        // meshes of every body so far (kMaxMeshes)
  std::vector<double> base_radius_given_;  // per base: its `radius:` [m], or 0
};

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_MODEL_PARSER_H_
