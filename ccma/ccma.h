// ccma: simulation and kinematic control of Constrained Collaborative Mobile
// Agents (Kumar & Coros). The one header a user includes:
//
//   #include <ccma/ccma.h>
//   const ccma::Model model = ccma::LoadModel("models/4dof_reduced.yaml");
//   ccma::ForwardProblem forward(model);          // built once; keeps a
//                                                 // reference to `model`
//   Eigen::VectorXd u = model.home_controls();    // 3 per base: x, y, theta
//   u[0] += 0.01;
//   ccma::ForwardResult r = forward.Solve(u);     // warm-started each call
//   if (r.assembled) std::cout << forward.end_effector().position;
//
// Link with `target_link_libraries(app ccma::ccma)` after
// `find_package(ccma CONFIG REQUIRED)`. Only the headers included here (and
// the ones they include) are installed; `*/internal/` and `cost_functions/`
// are the library's own.
#ifndef CCMA_CCMA_H_
#define CCMA_CCMA_H_

#include "execution/base_tracking.h"
#include "ccma/end_effector.h"
#include "collision/clearance.h"
#include "ccma/joint_coordinates.h"
#include "ccma/limits.h"
#include "ccma/loads.h"
#include "analyses/configuration_difference.h"
#include "analyses/mobility.h"
#include "analyses/moved_components.h"
#include "analyses/precision.h"
#include "analyses/statics.h"
#include "ccma/model.h"
#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "formats/obstacles_file.h"
#include "ccma/omni_wheels.h"
#include "ccma/rotation.h"
#include "ccma/state.h"
#include "formats/waypoints.h"
#include "problems/control_problem.h"
#include "analyses/design.h"
#include "analyses/design_objective.h"
#include "analyses/payload.h"
#include "problems/forward_problem.h"
#include "problems/compensated_control.h"
#include "problems/compensated_trajectory.h"
#include "problems/loaded_equilibrium.h"
#include "problems/path.h"
#include "problems/plan.h"
#include "execution/replay.h"
#include "problems/trajectory.h"
#include "analyses/workspace.h"

#endif  // CCMA_CCMA_H_
