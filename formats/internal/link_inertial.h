// A robot file's <inertial> as RobotLink::mass, com_W, inertia_W: the same
// conversion and checks for URDF, SDFormat and (to come) MJCF.
#ifndef CCMA_FORMATS_INTERNAL_LINK_INERTIAL_H_
#define CCMA_FORMATS_INTERNAL_LINK_INERTIAL_H_

#include <string>

#include <Eigen/Geometry>

#include "formats/robot_description.h"

namespace ccma::internal {

// `mass` [kg] at the origin of the inertial frame X_LI (in the link frame),
// with inertia I_I [kg m^2] about it in that frame's axes, onto `link`
// (already posed: X_WL). Throws ModelError "where: inertial: what" for a
// value that is not a finite number. Whether the values make a mass a model
// holds is analyses/robot_import.h's to judge (the collection's CAD exports
// give some links hundreds of tonnes).
void SetLinkInertial(double mass, const Eigen::Isometry3d& X_LI, const Eigen::Matrix3d& I_I, const std::string& where,
                     RobotLink* link);

}  // namespace ccma::internal

#endif  // CCMA_FORMATS_INTERNAL_LINK_INERTIAL_H_
