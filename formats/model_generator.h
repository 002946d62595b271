// Generated model files: the Stewart-like family of 6dof_six_agents and the
// legged family of 6dof_three_legged with any number of agents, for scaling
// studies and tests.
#ifndef CCMA_MODEL_GENERATOR_H_
#define CCMA_MODEL_GENERATOR_H_

#include <string>

namespace ccma {

struct StewartOptions {
  int agents = 6;                  // >= 3
  double base_radius = 0.65;       // m, bases on a circle around the origin
  double platform_radius = 0.15;   // m, spherical joints on the end-effector
  double platform_height = 0.6;    // m, end-effector point
  double post_height = 0.35;       // m, the horizontal revolute on each post
  double attachment_offset = 0.7;  // rad, +- angle between a base and its joint
};

// A model file (YAML text, model_format.md) of `agents` omni bases on a
// circle, legs attached alternately to either side on the end-effector.
// From 6 agents: reduced bases, each with a vertical revolute to a post, a
// horizontal revolute to a link and a spherical joint on the end-effector
// (every leg constrains one distance). Below 6: complete bases with the
// post welded on (F-R-S legs, two constraints each), so the model is rigid
// with its controls fixed either way. Throws std::invalid_argument for
// agents < 3.
std::string GenerateStewartModel(const StewartOptions& options);

// A Stewart-Gough platform with `agents` legs and no mobile base (>= 6): each
// leg a universal joint at the ground (`world`), an actuated prismatic joint
// `leg<i>` with limits [-0.1, 0.1] m, and a spherical joint on the platform
// (UPS); ground and platform points as in GenerateStewartModel. Throws
// std::invalid_argument for fewer than 6 legs.
std::string GenerateStewartGoughModel(const StewartOptions& options);

struct LeggedOptions {
  int agents = 3;                 // >= 3 quadrupeds
  double base_radius = 0.9;       // m, quadrupeds on a circle around the origin, facing it
  double body_height = 0.45;      // m, home height of each body
  double post_height = 0.1;       // m, the hinge above the body frame
  double platform_radius = 0.3;   // m, ball joints on the end-effector
  double platform_height = 0.95;  // m, end-effector point
};

// A 6-DOF platform on `agents` legged bases:
// each body carries an arm on a horizontal hinge (tangent to the circle),
// the arm holds the platform in a ball joint; rigid with the controls fixed.
// With 3 agents, the geometry of models/6dof_three_legged.yaml. Throws
// std::invalid_argument for agents < 3.
std::string GenerateLeggedModel(const LeggedOptions& options);

}  // namespace ccma

#endif  // CCMA_MODEL_GENERATOR_H_
