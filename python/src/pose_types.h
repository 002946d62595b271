// Small result types the Python API adds to the C++ ones: a solve's result
// carries the end-effector pose, the controls it was solved at and the
// configuration it reached, so a Python user gets one object per call whose
// to_dict() is the JSON of `ccma simulate` or `ccma control` (cli.md,
// "Python"; documents/simulate_document.h, control_document.h).
#ifndef CCMA_PYTHON_SRC_POSE_TYPES_H_
#define CCMA_PYTHON_SRC_POSE_TYPES_H_

#include <optional>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "ccma/end_effector.h"
#include "ccma/model.h"
#include "ccma/state.h"
#include "documents/control_document.h"
#include "documents/simulate_document.h"
#include "problems/compensated_control.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "problems/loaded_equilibrium.h"

namespace ccma::python {

// A forward solve's result and where it left the mechanism: the document
// layer's (documents/simulate_document.h), whose document is its to_dict().
using documents::ForwardSolution;
using documents::MakeForwardSolution;

// Whether the problem is at its model's home state and home controls.
bool AtHome(const ForwardProblem& problem);

using Vector6d = Eigen::Matrix<double, 6, 1>;

// ControlResult plus where it left the mechanism: the document layer's
// (documents/control_document.h), whose document is its to_dict().
using documents::ControlSolution;

// One body's absolute pose.
struct BodyPose {
  std::string name;
  Eigen::Vector3d position;   // p_WB [m]
  Eigen::Matrix3d rotation;   // R_WB
  Eigen::Vector4d quaternion; // [w, x, y, z] of R_WB
  Eigen::Vector3d rpy;        // R_WB as roll, pitch, yaw [rad]
};

BodyPose PoseOfBody(const Model& model, const State& s, int body);

// A state as Python sees it: one row per body (see below).
using StateArray = Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor>;

// The state as a (num_bodies x 7) array [qw, qx, qy, qz, px, py, pz] per row
// (the quaternion scalar first, as the `ccma` tool writes quaternions; the
// C++ storage, state.h, keeps it last), and back (quaternions normalised;
// throws std::invalid_argument on a wrong shape or a non-finite entry).
StateArray StateToArray(const State& s);
State StateFromArray(const Model& model, const Eigen::Ref<const StateArray>& a);
// Throws std::invalid_argument (ValueError) unless u holds one finite number
// within [-kMaxMagnitude, kMaxMagnitude] per control of `model`, with the
// message ForwardProblem gives.
void CheckControls(const Model& model, const Eigen::VectorXd& u);

}  // namespace ccma::python

#endif  // CCMA_PYTHON_SRC_POSE_TYPES_H_
