// The efforts `ccma view --trajectory=T.csv --dynamics=D.csv` colours the
// actuators by (viewer/scene_format.md, "efforts"; docs/viewer.md, "Colouring
// by effort"): D is `ccma dynamics --out` of the trajectory drawn, and at
// every frame each limited actuator's effort is taken as a share of its
// limit (analyses/internal/motion_limits.h: a joint's effort_limits, 1 at
// either end; a base's push_limit on the length of its (x, y) effort).
// Actuators without a limit are not coloured: there is nothing to judge
// their effort by.
#ifndef CCMA_VIEWER_FRAME_EFFORTS_H_
#define CCMA_VIEWER_FRAME_EFFORTS_H_

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ccma/model.h"
#include "viewer/view_frames.h"

namespace ccma::viewer {

struct LimitedActuator {
  std::string name;  // the joint's or the base's
  std::string kind;  // "effort" (effort_limits) or "push" (push_limit)
  int body = -1;     // the body it drives: the joint's body_b (body_a on the world), the base's body
};

struct FrameEfforts {
  std::vector<LimitedActuator> actuators;
  // Per frame, per actuator: |effort| / limit (above 1: beyond it); -1 where
  // the dynamics row did not assemble (empty effort cells).
  std::vector<std::vector<double>> shares;
  double max = 0;  // the largest share of every frame
};

// The shares at the frames drawn, read from the dynamics CSV `path`: its
// time_s and effort columns (EffortColumns), a row at each frame's time
// (within 1e-9 s relative; rows between frames, thinned away, are skipped).
// Throws ViewInputError naming the file (and line and column) for a bad
// cell, a missing column or a frame's time with no row (the dynamics of
// another trajectory), and std::invalid_argument when the model has no
// effort_limits or push_limit.
FrameEfforts ReadFrameEfforts(const Model& model, const std::string& path, const std::vector<ViewFrame>& frames);

// The scene's "efforts" object: actuators [{name, kind, body}], shares
// (rounded to 1e-7), max.
nlohmann::json FrameEffortsJson(const FrameEfforts& efforts);

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_FRAME_EFFORTS_H_
