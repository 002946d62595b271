// Compliance of a mechanism (model_format.md, "Compliance"): the stiffness of
// mobile bases, of actuated joints' motors and of joints' constrained
// directions. A model without any stiffness key is rigid.
//
// Spring directions of a joint (ccma/internal/joint_spring_directions.h):
// the directions a joint does not allow, measured at the joint's point in the
// frame of between[0]'s body (A). Translation first, then rotation:
//   revolute   translation x, y, z of A; rotation n1, n2
//   universal  translation x, y, z of A; rotation about a x b (normal to both axes)
//   prismatic  translation n1, n2; rotation x, y, z of A
//   fixed      translation x, y, z of A; rotation x, y, z of A
//   spherical  translation x, y, z of A
// with a the joint's axis (in A), n1 = x - (x.a)a normalised (x: A's x axis,
// its y axis where |x.a| > 0.9) and n2 = a x n1.
// Units: N/m for translation, N*m/rad for rotation.
#ifndef CCMA_STIFFNESS_H_
#define CCMA_STIFFNESS_H_

#include <vector>

#include <Eigen/Core>

namespace ccma {

// Stiffness values accepted in a model file (N/m or N*m/rad): every value
// lies in [kMinStiffness, kMaxStiffness], wide enough for a rubber mount and
// a steel weld, narrow enough that compliances stay finite in products.
constexpr double kMinStiffness = 1e-6;
constexpr double kMaxStiffness = 1e13;

// A mobile base's `stiffness: [kx, ky, ktheta]`: along the world x and y
// axes and about its heading; all zero when not given (rigid).
struct BaseStiffness {
  Eigen::Vector3d k = Eigen::Vector3d::Zero();  // N/m, N/m, N*m/rad
  bool given() const { return k.x() > 0; }
};

// A joint's stiffness: `axis` of its motor (actuated joints), and per
// constrained direction (order above) `translation` and `rotation`; an empty
// list means rigid in those directions.
struct JointStiffness {
  double axis = 0;                  // N/m or N*m/rad; 0: rigid motor
  std::vector<double> translation;  // empty or one per constrained translation
  std::vector<double> rotation;     // empty or one per constrained rotation
  bool has_springs() const { return !translation.empty() || !rotation.empty(); }
  bool given() const { return axis > 0 || has_springs(); }
};

}  // namespace ccma

#endif  // CCMA_STIFFNESS_H_
