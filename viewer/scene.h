// The viewer's scene (viewer/scene_format.md): a model's shapes derived from
// its joints, and per frame every body's pose, as one JSON document.
#ifndef CCMA_VIEWER_SCENE_H_
#define CCMA_VIEWER_SCENE_H_

#include <optional>
#include <string>
#include <vector>

#include "ccma/model.h"
#include "viewer/deflection_shape.h"
#include "viewer/frame_efforts.h"
#include "viewer/frame_loads.h"
#include "viewer/mesh_files.h"
#include "viewer/view_frames.h"
#include "viewer/workspace_cloud.h"

namespace ccma::viewer {

// The work bound of re-assembling the frames (forward solves, one per
// sub-step of ForwardProblem::Assemble): at most kMaxViewFrameSubsteps for one
// frame (20 m or rad of control change at the default max_control_step of
// 0.02) and kMaxViewSubsteps for the whole scene. A frame beyond either is not
// attempted: it counts as not assembled, and the mechanism stays at the last
// frame assembled (the next frame starts from there).
constexpr long kMaxViewFrameSubsteps = 1000;
constexpr long kMaxViewSubsteps = 200000;

struct SceneSummary {
  int frames = 0;
  int flagged_frames = 0;      // marked by the source or not assembled here
  int not_assembled = 0;       // frames whose E stayed above FlagEnergyFor(source), or beyond the bound
  int beyond_work_bound = 0;   // of which not attempted: beyond kMaxViewFrameSubsteps or kMaxViewSubsteps
  int branch_jumps = 0;        // frames reached by a jump to another branch
  int clearance_below_margin = 0;  // frames whose clearance is below collision.margin (collision geometry only)
  long workspace_points = 0;     // points of the workspace cloud (0 without one)
  long workspace_reachable = 0;  // of which reachable
  // With ColorBy::kLoad (else 0): the largest load of the page [N], and the
  // frames whose statics is not balanced or not determinate.
  double max_load = 0;
  int unbalanced_frames = 0;
  int indeterminate_frames = 0;
  // With a DeflectionRequest: the loaded shape drawn (else empty).
  std::optional<DeflectedShape> deflected;
  // With FrameEfforts (else empty / 0): the largest effort share of the
  // page, and the frames where some actuator is beyond its limit.
  std::optional<double> max_effort_share;
  int effort_frames_beyond_limit = 0;
};

// The residual energy E [m^2] above which a re-assembled frame counts as
// not assembled: the forward problem's assembly tolerance for a trajectory
// (its steps close exactly), the torn level for a replay (bases tracked with
// noise never sit exactly where the chain closes; ReplayOptions).
double FlagEnergyFor(const std::string& source);

// The scene for `frames` (empty: the model at home, one frame). Each frame
// is assembled from the previous one (ForwardProblem::Assemble, following
// the branch), within the work bound above; frames whose E stays above
// FlagEnergyFor(source), beyond the bound, or reached by a branch jump, are
// flagged. With collision geometry (model.collision.enabled), the scene's
// "collision" object holds the shapes and each frame its smallest clearance
// (MinimumClearance at the state drawn) and pair; a frame whose clearance is
// below collision.margin (by more than 1e-9 m) is flagged too. Without, no
// collision key appears. `source` is "model", "trajectory",
// "replay" or "workspace". With `workspace`, the scene's "workspace" object
// holds its cloud and the scale covers it. With `meshes` (ReadMeshFiles of
// the same model), the scene carries the mesh files and each body its
// meshes' poses; without, no mesh is mentioned. With ColorBy::kLoad, the
// scene's "loads" object holds every frame's body loads (FrameLoads, at the
// state drawn and its controls) and their maximum; throws
// std::invalid_argument, before any frame is assembled, when the statics
// are beyond FrameLoads's bounds. With `deflection` (a static view: at most
// one frame), the scene's "deflection" object holds the loaded shape at the
// state drawn (ComputeDeflectedShape; summary->deflected); throws
// DeflectionError when that frame is not assembled or the loaded
// equilibrium is beyond its bounds. Without, no deflection key appears.
// With `efforts` (ReadFrameEfforts of the same frames), the scene's
// "efforts" object holds every frame's actuator shares of their limits.
// Returns the JSON text
// (numbers rounded to 1e-7: display precision, a tenth of a micrometre;
// never NaN).
std::string BuildScene(const Model& model, const std::vector<ViewFrame>& frames, const std::string& source,
                       SceneSummary* summary, const WorkspaceCloud* workspace = nullptr,
                       const MeshFiles* meshes = nullptr, ColorBy color_by = ColorBy::kBody,
                       const DeflectionRequest* deflection = nullptr, const FrameEfforts* efforts = nullptr);

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_SCENE_H_
