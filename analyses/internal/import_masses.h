// The source's masses as a model file can hold them (analyses/robot_import.h):
// every link's mass in [0, 1e4] kg, centre of mass within 1e4 m, inertia
// entries within 1e4 kg m^2 and physical (ccma/mass_properties.h). Some CAD
// exports are not (the collection's 5bar_linkage weighs 654 t a link): then
// none is kept, and import says so, rather than weigh a robot wrongly.
#ifndef CCMA_ANALYSES_INTERNAL_IMPORT_MASSES_H_
#define CCMA_ANALYSES_INTERNAL_IMPORT_MASSES_H_

#include <string>

#include "ccma/model.h"
#include "formats/robot_description.h"

namespace ccma::internal {

// "" when every link's inertial can be kept; otherwise why the first that
// cannot, naming it (the caller drops them all).
std::string InertialsBeyondAModel(const RobotDescription& robot);

// Every body's mass, centre of mass and inertia set to none.
void DropMasses(Model* model);

}  // namespace ccma::internal

#endif  // CCMA_ANALYSES_INTERNAL_IMPORT_MASSES_H_
