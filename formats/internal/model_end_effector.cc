// `end_effector`: the body that carries it, the controlled point and the
// controlled components of its pose.
#include <string>

#include "ccma/internal/format.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

void ModelParser::ParseEndEffector(const YAML::Node& ee) {
  r_.CheckKeys(ee, {"body", "point", "controlled", "payload"}, "end_effector");
  EndEffector& out = model_.end_effector;
  const YAML::Node body = r_.Require(ee, "body", "end_effector");
  if (r_.String(body, "end_effector.body") == "world") {
    r_.Fail(body, "end_effector.body", "the end-effector must be on a body, not on 'world'");
  }
  out.body = BodyAt(body, "end_effector.body");
  const Body& frame = model_.bodies[out.body];
  out.p_W_home = r_.Vector3(r_.Require(ee, "point", "end_effector"), "end_effector.point", "m");
  out.p_B = frame.R_WB_home.transpose() * (out.p_W_home - frame.p_WB_home);
  const YAML::Node controlled =
      r_.Sequence(r_.Require(ee, "controlled", "end_effector"), "end_effector.controlled");
  if (controlled.size() == 0) r_.Fail(controlled, "end_effector.controlled", "must name at least one component");
  for (std::size_t c = 0; c < controlled.size(); ++c) {
    const std::string path = Indexed("end_effector.controlled", c);
    const std::string component = r_.String(controlled[c], path);
    int index = -1;
    for (int k = 0; k < 6; ++k) {
      if (component == kEndEffectorComponentNames[k]) index = k;
    }
    if (index < 0) {
      r_.Fail(controlled[c], path, "unknown component " + Quote(component) + " (known: x y z roll pitch yaw)");
    }
    if (out.controlled[index]) r_.Fail(controlled[c], path, "component '" + component + "' listed twice");
    out.controlled[index] = true;
  }
}

}  // namespace internal
}  // namespace ccma
