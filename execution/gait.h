// A trotting gait's effect on a legged base's body (docs/cli.md, "Legged
// bases in the output"): while the base walks, its body bobs (height) and
// sways (roll) at the gait frequency. `ccma replay` adds it to where the
// legged bases really are, and reports how much of the end-effector's error
// it causes.
#ifndef CCMA_EXECUTION_GAIT_H_
#define CCMA_EXECUTION_GAIT_H_

#include <string>

#include <Eigen/Core>

#include "ccma/model.h"

namespace ccma {

struct Gait {
  double hz = 2.0;         // gait frequency, (0, 100] Hz
  double bob_m = 0.01;     // amplitude of the body's height oscillation, [0, 1] m
  double sway_rad = 0.02;  // amplitude of its roll oscillation, [0, 0.5] rad

  // False, with `why` naming the field and its unit, when out of range.
  bool IsValid(std::string* why) const;
};

// Whether any base of `model` is legged (only then does a gait apply).
bool HasLeggedBases(const Model& model);

// Adds the gait at time t [s] (from the replay's start) to the height and
// roll of every legged base that walks (set_velocity, the set-points' rate of
// change, moves its x or y); a base standing still has none:
//   height += bob_m sin(2 pi hz t),  roll += sway_rad sin(2 pi hz t):
// both symmetric about the set-point (up and down, left and right) and zero
// at the start, so a walk from rest begins without a jump.
void ApplyGait(const Model& model, const Gait& gait, double t, const Eigen::VectorXd& set_velocity,
               Eigen::VectorXd* controls);

}  // namespace ccma

#endif  // CCMA_EXECUTION_GAIT_H_
