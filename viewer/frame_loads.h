// The loads `ccma view --color_by=load` colours the links by
// (viewer/scene_format.md, "loads"; docs/viewer.md, "Colouring by load"): at
// every frame's state and controls, the statics of the mechanism under
// gravity on the model's masses and payload (analyses/statics.h, no external
// wrench), and per body the largest reaction force [N] among the joints that
// touch it (a joint's reaction is equal and opposite on its two bodies, so
// its magnitude is the same for both).
#ifndef CCMA_VIEWER_FRAME_LOADS_H_
#define CCMA_VIEWER_FRAME_LOADS_H_

#include <vector>

#include <Eigen/Core>

#include "analyses/statics.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma::viewer {

// What the links of a page are coloured by: their kind (the palette), or
// their load (`--color_by=load`).
enum class ColorBy { kBody, kLoad };

// The work bound of the statics of one page: each frame's dense solve costs
// about rows x coordinates x min(rows, coordinates) operations (the
// constraint Jacobian's orthogonal decomposition), summed over the frames.
// 2e10 (some 20 s) holds 2000 frames of a mechanism of 200 rows and 180
// coordinates (1.3e10), or a few frames of a 100-leg Stewart platform (1700
// rows x 1206 coordinates, 2.5e9 each).
constexpr double kMaxViewStaticsWork = 2e10;

// Whether the model has a mass or a payload: without, every load is 0 and
// no statics is solved.
bool HasMasses(const Model& model);

// Per body of `model` (Model::bodies order): the largest |force| [N] of the
// reactions in `report` (ComputeStatics of the same model) of the joints
// that touch it; 0 for a body that no joint touches.
std::vector<double> BodyLoads(const Model& model, const StaticsReport& report);

// The loads of a page's frames, added in frame order.
class FrameLoads {
 public:
  // For a page of `frames` frames. Throws std::invalid_argument (its message
  // gives the sizes and the bound) when one frame's statics is beyond
  // kMaxStaticsEntries or all of them beyond kMaxViewStaticsWork; nothing is
  // solved then.
  FrameLoads(const Model& model, int frames);

  // The statics at state s and controls u (the state drawn for the frame).
  void Add(const State& s, const Eigen::VectorXd& u);

  bool masses() const { return masses_; }
  const std::vector<std::vector<double>>& body_loads() const { return loads_; }  // per frame, per body [N]
  const std::vector<bool>& balanced() const { return balanced_; }        // per frame (StaticsReport::balanced)
  const std::vector<bool>& determinate() const { return determinate_; }  // per frame (StaticsReport::determinate)
  double max() const { return max_; }  // the largest load of every frame and body [N]; 0 without frames

 private:
  const Model& model_;
  bool masses_ = false;
  std::vector<std::vector<double>> loads_;
  std::vector<bool> balanced_, determinate_;
  double max_ = 0;
};

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_FRAME_LOADS_H_
