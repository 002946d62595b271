// A ccma::Model rebuilt as a Simbody system, for the head-to-head benchmark:
// the same bodies, joints and end-effector, described the way Simbody wants
// them (internal coordinates on a spanning tree, loop constraints for the rest).
//
//  * Tree: every mobile base hangs from Ground on a Planar mobilizer whose
//    q = (theta, x, y) is prescribed from the base's controls along a track
//    (base_track_motion.h). Then, in passes over the joints in file order, a
//    joint with exactly one end already in the tree (Ground counts) becomes
//    the mobilizer of its other body: revolute -> Pin (its frames' z along
//    the joint axis), spherical -> Ball, universal -> Universal (x along the
//    first axis, y along the second), fixed -> Weld.
//  * Loops: every remaining joint becomes constraints between its two bodies:
//    spherical -> Constraint::Ball (3 equations); revolute -> Ball plus two
//    Constraint::ConstantAngle at 90 degrees between the axis fixed in B and
//    two directions perpendicular to the axis fixed in A (5 equations: the
//    construction Simbody's Constraint.h recommends for aligning two axes,
//    since one ConstantAngle cannot hold an angle of 0 well); universal ->
//    Ball plus one ConstantAngle at 90 degrees between its two axes;
//    fixed -> Constraint::Weld.
//  * Frames: each Simbody body frame is the ccma body frame (model.h), and
//    every mobilizer's F and M frames coincide at the model's home
//    configuration, so q = 0 on the passive joints is home and a point given
//    in a ccma body frame (the end-effector's p_B) is the same in Simbody.
//
// Kinematics only: masses and inertias are placeholders (1 kg, unit inertia),
// valid for Simbody and irrelevant to position projection and assembly.
// Prismatic and actuated joints are not modelled (throws std::runtime_error).
#ifndef CCMA_BENCHMARKS_SIMBODY_SIMBODY_MECHANISM_H_
#define CCMA_BENCHMARKS_SIMBODY_SIMBODY_MECHANISM_H_

#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Simbody.h>

#include "ccma/model.h"

namespace ccma::simbody_benchmark {

class SimbodyMechanism {
 public:
  // controls: the base controls per step (model.h); time t = k in Simbody
  // prescribes controls[k] (base_track_motion.h). The model must outlive this.
  SimbodyMechanism(const Model& model, std::shared_ptr<const std::vector<Eigen::VectorXd>> controls);
  SimbodyMechanism(const SimbodyMechanism&) = delete;
  SimbodyMechanism& operator=(const SimbodyMechanism&) = delete;

  const SimTK::MultibodySystem& system() const { return system_; }
  const SimTK::SimbodyMatterSubsystem& matter() const { return matter_; }

  // The default state (home: passive q = 0) at time 0, realized to Model.
  SimTK::State HomeState() const;
  // p_WE [m]: the end-effector point in world; `state` realized to Position.
  Eigen::Vector3d EndEffectorPosition(const SimTK::State& state) const;

  // Disables, in file order, each ConstantAngle equation that is a linear
  // combination of the enabled ones at `state`'s configuration (rank of
  // d(position errors)/dq over the free q's, the bases' prescribed q left
  // out), for solvers that need independent equations: Simbody's Assembler
  // hands constraints to an interior-point optimiser (Ipopt) that rejects
  // more equations than free q ("Not enough degrees of freedom"), while
  // projectQ's pseudo-inverse accepts them. Structurally redundant rows (the
  // parallel hinge axes of 4dof_reduced's legs) stay satisfied when dropped;
  // the end-effector check in head_to_head.cc would show it otherwise.
  // `state` is realized to Position at its time. Returns the number of
  // equations disabled; *remaining_redundant (may be null) gets how many
  // enabled equations are still dependent (0: all independent).
  int DisableRedundantAngleConstraints(SimTK::State* state, int* remaining_redundant) const;

  // Sizes, for the report.
  int num_tree_joints() const { return num_tree_joints_; }    // passive mobilizers
  int num_loop_joints() const { return num_loop_joints_; }    // joints closed by constraints
  int num_constraint_equations() const { return num_constraint_equations_; }

 private:
  const Model& model_;
  SimTK::MultibodySystem system_;
  SimTK::SimbodyMatterSubsystem matter_;
  std::vector<SimTK::MobilizedBody> mobods_;  // per ccma body (Model::bodies)
  std::vector<SimTK::Constraint> angle_constraints_;  // the loop closures' ConstantAngle equations
  int num_tree_joints_ = 0, num_loop_joints_ = 0, num_constraint_equations_ = 0;
};

}  // namespace ccma::simbody_benchmark

#endif  // CCMA_BENCHMARKS_SIMBODY_SIMBODY_MECHANISM_H_
