// A model written as MuJoCo MJCF (`ccma export --format=mjcf`, docs/cli.md;
// contract: model_format.md, "MuJoCo MJCF"): a tree of bodies whose loops
// are closed by equality constraints, written at the assembled home so that
// every equality holds where MuJoCo loads the file.
//  * the tree: a spanning tree of the joint graph that keeps prismatic and
//    universal joints first (MuJoCo has no equality for them), then
//    revolute, fixed and spherical ones, so that the joints cut are the ones
//    an equality expresses exactly: a spherical cut as a `connect` at its
//    point, a fixed cut as a `weld`, a revolute cut as two `connect`s on its
//    axis (at its point and 0.1 m along the axis). A loop that could only be
//    cut at a prismatic or universal joint is refused;
//  * every body of the model is a <body> with its own frame at home (pos and
//    quat relative to its parent body); a tree joint is written in its child
//    body: revolute `hinge`, prismatic `slide` (their axis signed so that
//    qpos is ccma's q; `ref` = q_home, so qpos0 = q_home; limits as `range`),
//    spherical `ball`, universal two `hinge`s (the parent's axis first),
//    fixed nothing (welded);
//  * a mobile base's body hangs from the world by `slide` x, `slide` y and
//    `hinge` z (world axes; a legged base then `slide` z, `hinge` pitch,
//    `hinge` roll, its six controls), each `ref` its home control: every
//    control's value is its joint's qpos;
//  * `<inertial>` from mass, com and inertia; a body without a mass gets
//    kMjcfMinMass and kMjcfMinInertia (MuJoCo needs them on moving bodies);
//    the end-effector's payload is a body `payload` welded to its body;
//  * a `<position>` actuator per control, named after it (a base's
//    BASE_x ..., an actuated joint's name), kp = kMjcfActuatorKp; every
//    joint has armature kMjcfArmature and damping kMjcfDamping (stable at
//    kMjcfTimestep with MuJoCo's implicit integrator);
//  * the equalities' solref/solimp (kMjcfSolref, kMjcfSolimp): stiff enough to keep
//    a loop closed within 1e-4 m under gravity and the actuators;
//  * gravity, a `<site name="end_effector">` at the controlled point, and a
//    `<keyframe>` `home` (qpos0, the controls at home).
// Numbers are written in the fewest digits that read back exactly.
#ifndef CCMA_FORMATS_MJCF_WRITER_H_
#define CCMA_FORMATS_MJCF_WRITER_H_

#include <string>

#include "ccma/model.h"

namespace ccma {

// The physical settings of an export (why each: docs/import.md, "MuJoCo").
constexpr double kMjcfTimestep = 0.001;      // s
constexpr double kMjcfActuatorKp = 1e5;      // N/m or N*m/rad
constexpr double kMjcfArmature = 1.0;        // kg or kg*m^2, added to every joint's inertia
// N*s/m or N*m*s/rad: light (0.03 of critical for the armature alone). Over-
// actuated controls hold the mechanism against each other through the soft
// equalities until they agree, and joint damping slows that relaxation in
// proportion: critical damping (632) left 6dof_asymmetric 2 mm off after
// 2 s, 20 leaves it within 1e-6 m after 1 s; the oscillation it leaves
// decays as exp(-10 t).
constexpr double kMjcfDamping = 20.0;
constexpr double kMjcfMinMass = 1e-3;        // kg, for a body without mass
constexpr double kMjcfMinInertia = 1e-6;     // kg*m^2, its principal moments
constexpr double kMjcfAnchorSpacing = 0.1;   // m, between a revolute cut's two connects
constexpr const char* kMjcfSolref = "0.002 1";
constexpr const char* kMjcfSolimp = "0.99 0.999 0.001 0.5 2";

struct MjcfExport {
  std::string mjcf;    // the document
  int bodies = 0;      // <body> elements
  int joints = 0;      // <joint> elements
  int equalities = 0;  // connect and weld elements
  int actuators = 0;   // position actuators: one per control
  int loops = 0;       // joints of the model cut from the tree
};

// The model (any valid one, as LoadModel returns it) as MJCF. Throws
// std::invalid_argument naming the joint when a loop can only be cut at a
// prismatic or universal joint.
MjcfExport WriteMjcf(const Model& model);

}  // namespace ccma

#endif  // CCMA_FORMATS_MJCF_WRITER_H_
