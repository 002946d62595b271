// The loaded shape `ccma view --deflection=SCALE` draws (viewer/scene_format.md,
// "deflection"; docs/viewer.md, "Deflection"): the nonlinear loaded
// equilibrium of a compliant model (problems/loaded_equilibrium.h, the one
// `ccma simulate --loaded` prints) at the state drawn, and every body's pose
// with its displacement from the rigid assembly multiplied by SCALE, so that
// deflections of micrometres show at the scale of the mechanism.
// Units: m, rad, N, N*m.
#ifndef CCMA_VIEWER_DEFLECTION_SHAPE_H_
#define CCMA_VIEWER_DEFLECTION_SHAPE_H_

#include <stdexcept>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ccma/loads.h"
#include "ccma/model.h"
#include "ccma/state.h"
#include "problems/loaded_equilibrium.h"

namespace ccma::viewer {

// Why the loaded shape cannot be drawn (a usage error of the command).
class DeflectionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The bounds of SCALE: finite, > 0 and at most kMaxDeflectionScale (a
// micrometre drawn as at most a metre).
constexpr double kMaxDeflectionScale = 1e6;

// What --deflection asks for: the exaggeration and the external wrench on
// the end-effector body (gravity on the masses and payload always).
struct DeflectionRequest {
  double scale = 1;
  ExternalWrench wrench;
};

struct DeflectedShape {
  double scale = 1;
  LoadedEquilibrium equilibrium;  // state: the loaded configuration (not exaggerated)
  // Per body (Model::bodies order): its drawn pose, p_WB = p_rigid + scale
  // (p_loaded - p_rigid), R_WB = Exp(scale Log(R_loaded R_rigid^T)) R_rigid.
  std::vector<Eigen::Vector3d> p_WB_drawn;
  std::vector<Eigen::Quaterniond> q_WB_drawn;
  // Per body: the largest displacement [m] (not exaggerated) among its frame
  // origin, its joint points and (its body's) the end-effector point.
  std::vector<double> body_deflection_m;
  double max_deflection_m = 0;  // the largest of them
  int max_body = 0;             // whose
};

// The loaded shape at the rigid assembly `rigid` and controls u. Throws
// DeflectionError when the request's scale is out of bounds or the loaded
// equilibrium's system is beyond its bound (SolveLoadedEquilibrium).
DeflectedShape ComputeDeflectedShape(const Model& model, const State& rigid, const Eigen::VectorXd& u,
                                     const DeflectionRequest& request);

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_DEFLECTION_SHAPE_H_
