// Inverse dynamics judged by MuJoCo (Debian's libmujoco, 2.2.2): a spatial
// arm of three motors in series (about z, then two about -y), with masses,
// off-centre coms and full inertia tensors, exported by `ccma export
// --format=mjcf` and loaded by MuJoCo's own compiler. At seeded random
// positions, rates and accelerations of the motors, MuJoCo's mj_inverse
// (the recursive Newton-Euler of its own kinematic tree, armature and
// damping set to 0) gives the joint torques; ccma's InverseDynamics (the
// constraint multipliers of its maximal coordinates) must give the same: to
// 1e-9 of the largest with principal-axis inertias, to 2e-8 with full
// tensors (MuJoCo's compiler diagonalises a fullinertia; measured 3e-8 N m
// of 5 N m on the yaw motor, 0 with the products of inertia set to 0). An open chain: for closed loops MuJoCo's equalities are
// soft, and the closed forms and the d'Alembert check
// (tests/dynamics_test.cc, tests/dalembert_test.cc) judge instead.
#include <cmath>
#include <fstream>
#include <memory>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <Eigen/Core>

#include "analyses/dynamics.h"
#include "formats/mjcf_writer.h"
#include "formats/model_loader.h"
#include "problems/forward_problem.h"
#include "tool_run.h"

namespace ccma {
namespace mujoco_dynamics_test {

constexpr char kArm[] =
    "name: spatial_arm\n"
    "bodies:\n"
    "  - {name: turret, position: [0, 0, 0.1], mass: 3.0, com: [0.01, -0.02, 0.05],"
    " inertia: [0.03, 0.025, 0.02, 0.002, -0.001, 0.003]}\n"
    "  - {name: upper, position: [0, 0, 0.3], mass: 2.0, com: [0.25, 0.01, 0.0],"
    " inertia: [0.012, 0.05, 0.045, 0.001, 0.0005, -0.002]}\n"
    "  - {name: fore, position: [0.5, 0, 0.3], mass: 1.2, com: [0.2, -0.01, 0.02],"
    " inertia: [0.006, 0.02, 0.018, -0.0005, 0.0008, 0.001]}\n"
    "joints:\n"
    "  - {name: yaw, type: revolute, actuated: true, between: [world, turret], point: [0, 0, 0.1], axis: [0, 0, 1]}\n"
    "  - {name: shoulder, type: revolute, actuated: true, between: [turret, upper], point: [0, 0, 0.3],"
    " axis: [0, -1, 0]}\n"
    "  - {name: elbow, type: revolute, actuated: true, between: [upper, fore], point: [0.5, 0, 0.3],"
    " axis: [0, -1, 0]}\n"
    "end_effector: {body: fore, point: [0.9, 0, 0.3], controlled: [x, y, z]}\n";

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

// The arm with its products of inertia, or with them set to 0.
std::string Arm(bool products) {
  std::string text = kArm;
  if (products) return text;
  for (const char* p : {"0.002, -0.001, 0.003]", "0.001, 0.0005, -0.002]", "-0.0005, 0.0008, 0.001]"}) {
    text.replace(text.find(p), std::string(p).size(), "0, 0, 0]");
  }
  return text;
}

// ccma's torques against MuJoCo's at seeded trials, within `tolerance` of the largest.
void ExpectMuJoCosTorques(bool products, double tolerance) {
  const Model model = LoadModelFromString(Arm(products), "spatial_arm.yaml");
  const std::string path = testing::ScratchPath("mujoco_dynamics", "spatial_arm.xml");
  std::ofstream(path) << WriteMjcf(model).mjcf;
  char error[1000] = "";
  const std::unique_ptr<mjModel, MjModelDeleter> m(mj_loadXML(path.c_str(), nullptr, error, sizeof error));
  ASSERT_TRUE(m) << error;
  ASSERT_EQ(m->nv, 3);
  ASSERT_EQ(m->nu, 3);
  for (int i = 0; i < m->nv; ++i) m->dof_armature[i] = m->dof_damping[i] = 0;  // ccma models neither
  const std::unique_ptr<mjData, MjDataDeleter> d(mj_makeData(m.get()));
  const InverseDynamics dynamics(model);
  ForwardProblem forward(model);
  std::mt19937 rng(52);
  std::uniform_real_distribution<double> uniform(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd u(3), du(3), ddu(3);
    for (int i = 0; i < 3; ++i) u[i] = 1.2 * uniform(rng);
    for (int i = 0; i < 3; ++i) du[i] = 2.0 * uniform(rng);
    for (int i = 0; i < 3; ++i) ddu[i] = 5.0 * uniform(rng);
    ASSERT_TRUE(forward.Assemble(u).assembled) << trial;
    const Eigen::VectorXd e =
        dynamics.At(forward.state(), forward.controls(), du, ddu).efforts.control_efforts;
    // MuJoCo: each motor's joint at the control (its actuator's length), the
    // rates and accelerations as its qvel and qacc.
    for (int i = 0; i < m->nu; ++i) {
      const int joint = m->actuator_trnid[2 * i];
      d->qpos[m->jnt_qposadr[joint]] = u[i];
      d->qvel[m->jnt_dofadr[joint]] = du[i];
      d->qacc[m->jnt_dofadr[joint]] = ddu[i];
    }
    mj_inverse(m.get(), d.get());
    double largest = 0;
    for (int i = 0; i < m->nu; ++i) largest = std::max(largest, std::abs(e[i]));
    ASSERT_GT(largest, 1.0);
    for (int i = 0; i < m->nu; ++i) {
      ASSERT_NEAR(d->actuator_length[i], u[i], 1e-12) << "the exported joint's position is not the control";
      const double tau = d->qfrc_inverse[m->jnt_dofadr[m->actuator_trnid[2 * i]]];
      EXPECT_NEAR(e[i], tau, tolerance * largest) << mj_id2name(m.get(), mjOBJ_ACTUATOR, i) << " trial " << trial;
    }
  }
}

TEST(MujocoInverseDynamics, ASpatialArmsTorquesAreMuJoCosRecursiveNewtonEuler) {
  ExpectMuJoCosTorques(false, 1e-9);
  ExpectMuJoCosTorques(true, 2e-8);
}

}  // namespace mujoco_dynamics_test
}  // namespace ccma
