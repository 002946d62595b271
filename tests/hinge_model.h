// A small model shared by the tests of joint limits: one omni base carrying
// a post, and an arm on an actuated, limited hinge about x (limits -0.2 and
// 0.3 rad). The end-effector point 0.2 m along y swings up as q grows, so
// z = 0.3 + 0.2 sin(q) needs q = asin((z - 0.3) / 0.2).
#ifndef CCMA_TESTS_HINGE_MODEL_H_
#define CCMA_TESTS_HINGE_MODEL_H_

namespace ccma {

inline constexpr char kHinge[] = R"(name: limited_hinge
bodies:
  - {name: post, position: [0, 0, 0.1]}
  - {name: arm, position: [0, 0, 0.3]}
mobile_bases:
  - {name: base0, type: omni, actuation: complete, pose: [0, 0, 0]}
joints:
  - {type: fixed, between: [base0, post], point: [0, 0, 0.1]}
  - {name: hinge, type: revolute, actuated: true, limits: [-0.2, 0.3], between: [post, arm], point: [0, 0, 0.3], axis: [1, 0, 0]}
end_effector: {body: arm, point: [0, 0.2, 0.3], controlled: [x, y, z]}
)";

}  // namespace ccma

#endif  // CCMA_TESTS_HINGE_MODEL_H_
