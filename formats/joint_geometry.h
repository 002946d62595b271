// A joint's geometry from world coordinates at home into its two bodies'
// frames: what the loader does with a joint's `point`, `axis` and `axes`,
// for code that builds a Model without a file (importers, analyses).
#ifndef CCMA_FORMATS_JOINT_GEOMETRY_H_
#define CCMA_FORMATS_JOINT_GEOMETRY_H_

#include <Eigen/Core>

#include "ccma/model.h"

namespace ccma {

// Fills joint->p_A, p_B and the axes and reference directions of its type
// from world coordinates at home, using the home poses of A and B (`world`
// when the joint's body index is kWorld):
//  p_W: the joint point [m]; a_W: unit axis (revolute, prismatic) or the
//  axis fixed in A (universal); b_W: universal only, the unit axis fixed in
//  B, exactly perpendicular to a_W. Other arguments are ignored by types
//  that have no use for them. The joint holds exactly at the home poses.
void SetJointGeometry(const Model& model, const Eigen::Vector3d& p_W, const Eigen::Vector3d& a_W,
                      const Eigen::Vector3d& b_W, Joint* joint);

}  // namespace ccma

#endif  // CCMA_FORMATS_JOINT_GEOMETRY_H_
