// Compliance (model_format.md, "Compliance"): `stiffness` on mobile bases
// ([kx, ky, ktheta]) and on joints (a number for an actuated joint's motor,
// or {axis, translation, rotation}). Unlike other numbers of a model file,
// stiffness is not bounded by kMaxMagnitude: it lies in [kMinStiffness,
// kMaxStiffness] (ccma/stiffness.h).
#include <cmath>
#include <string>

#include "ccma/internal/format.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {
namespace {

constexpr const char* kStiffnessRotationUnit = "N*m/rad";
constexpr const char* kStiffnessTranslationUnit = "N/m";

}  // namespace

double ModelParser::StiffnessValue(const YAML::Node& node, const std::string& path, const char* unit) const {
  if (!node.IsScalar()) r_.Fail(node, path, std::string("must be a number (") + unit + ")");
  double value = 0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    r_.Fail(node, path, "must be a number, got " + Quote(node.Scalar()));
  }
  if (!std::isfinite(value)) r_.Fail(node, path, "must be a finite number");
  if (!(value > 0)) r_.Fail(node, path, std::string("must be positive (") + unit + "), got " + FormatG(value));
  if (value < kMinStiffness || value > kMaxStiffness) {
    r_.Fail(node, path, Quote(node.Scalar()) + " must lie in [" + FormatG(kMinStiffness) + ", " +
                            FormatG(kMaxStiffness) + "] (" + unit + ")");
  }
  return value;
}

BaseStiffness ModelParser::ParseBaseStiffness(const YAML::Node& node, const std::string& path) const {
  BaseStiffness out;
  if (!YamlReader::Has(node, "stiffness")) return out;
  const YAML::Node list = node["stiffness"];
  const std::string at = path + ".stiffness";
  if (!list.IsSequence() || list.size() != 3) {
    r_.Fail(list, at, "must be a list of 3 positive numbers [kx, ky, ktheta] (N/m, N/m, N*m/rad)");
  }
  for (int i = 0; i < 3; ++i) {
    out.k[i] = StiffnessValue(list[i], Indexed(at, static_cast<std::size_t>(i)), i < 2 ? "N/m" : "N*m/rad");
  }
  return out;
}

// `count` values from a number (the same in every direction) or a list of
// exactly `count` numbers.
std::vector<double> ModelParser::StiffnessValues(const YAML::Node& node, const std::string& path, int count,
                                                 const char* unit) const {
  if (node.IsScalar()) return std::vector<double>(static_cast<std::size_t>(count), StiffnessValue(node, path, unit));
  if (!node.IsSequence() || node.size() != static_cast<std::size_t>(count)) {
    r_.Fail(node, path, "must be a number or a list of " + std::to_string(count) + " numbers (" + unit +
                            "), one per constrained direction");
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < node.size(); ++i) out.push_back(StiffnessValue(node[i], Indexed(path, i), unit));
  return out;
}

void ModelParser::ParseJointStiffness(const YAML::Node& node, const std::string& path, Joint* joint) const {
  if (!YamlReader::Has(node, "stiffness")) return;
  const YAML::Node value = node["stiffness"];
  const std::string at = path + ".stiffness";
  const char* axis_unit = joint->type == JointType::kRevolute ? kStiffnessRotationUnit : kStiffnessTranslationUnit;
  if (value.IsScalar()) {
    if (!joint->actuated) {
      r_.Fail(value, at, "a number is the stiffness of an actuated joint's motor; a passive joint's "
                         "constrained directions take {translation: K, rotation: K}");
    }
    joint->stiffness.axis = StiffnessValue(value, at, axis_unit);
    return;
  }
  if (!value.IsMap() || value.size() == 0) {
    r_.Fail(value, at, "must be a number (an actuated joint's motor) or a mapping with axis, translation, rotation");
  }
  for (const auto& entry : value) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "";
    if (key != "axis" && key != "translation" && key != "rotation") {
      r_.Fail(entry.first, at, "unknown key " + Quote(key) + " (known: axis, translation, rotation)");
    }
  }
  if (YamlReader::Has(value, "axis")) {
    if (!joint->actuated) r_.Fail(value["axis"], at + ".axis", "only an actuated joint has a motor stiffness");
    joint->stiffness.axis = StiffnessValue(value["axis"], at + ".axis", axis_unit);
  }
  if (YamlReader::Has(value, "translation")) {
    joint->stiffness.translation = StiffnessValues(value["translation"], at + ".translation",
                                                   TranslationSpringCount(joint->type), kStiffnessTranslationUnit);
  }
  if (YamlReader::Has(value, "rotation")) {
    const int count = RotationSpringCount(joint->type);
    if (count == 0) {
      r_.Fail(value["rotation"], at + ".rotation",
              std::string("a ") + JointTypeName(joint->type) + " joint allows every rotation: it has no rotation stiffness");
    }
    joint->stiffness.rotation = StiffnessValues(value["rotation"], at + ".rotation", count, kStiffnessRotationUnit);
  }
  if (!joint->stiffness.given()) r_.Fail(value, at, "must give axis, translation or rotation");
}

}  // namespace internal
}  // namespace ccma
