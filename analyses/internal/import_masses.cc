#include "analyses/internal/import_masses.h"

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "ccma/mass_properties.h"

namespace ccma::internal {

std::string InertialsBeyondAModel(const RobotDescription& robot) {
  for (const RobotLink& link : robot.links) {
    const std::string name = "link " + Quote(link.name) + ": <inertial> ";
    if (!(link.mass >= 0 && link.mass <= kMaxMagnitude)) {
      return name + "mass " + FormatG(link.mass) + " kg is outside [0, 1e4] kg";
    }
    if (link.com_W.cwiseAbs().maxCoeff() > kMaxMagnitude) return name + "centre of mass lies beyond 1e4 m";
    if (link.inertia_W.cwiseAbs().maxCoeff() > kMaxMagnitude) {
      return name + "inertia " + FormatG(link.inertia_W.cwiseAbs().maxCoeff()) + " kg*m^2 is beyond 1e4 kg*m^2";
    }
    std::string why;
    if (!IsPhysicalInertia(link.inertia_W, &why)) return name + "inertia " + why;
  }
  return "";
}

void DropMasses(Model* model) {
  for (Body& body : model->bodies) body.inertia = MassProperties();
}

}  // namespace ccma::internal
