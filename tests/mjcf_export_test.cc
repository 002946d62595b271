// `ccma export --format=mjcf` judged by MuJoCo itself (Debian's libmujoco,
// 2.2.2): every bundled and generated model loads; at qpos0 every equality
// holds, each connect's anchors lie on the cut joint, the end_effector site
// and every body are where ccma puts them at home, and MuJoCo's mobility
// equals ccma's; held by its actuators under gravity the loops stay closed
// and the actuator forces settle to ccma statics' efforts; driven to other
// controls the end-effector settles where ccma simulate puts it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <Eigen/Dense>

#include "analyses/mobility.h"
#include "analyses/statics.h"
#include "bundled_models.h"
#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "formats/mjcf_writer.h"
#include "ccma/end_effector.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "tool_run.h"

namespace ccma {
namespace mjcf_export_test {

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using MjModelPtr = std::unique_ptr<mjModel, MjModelDeleter>;
using MjDataPtr = std::unique_ptr<mjData, MjDataDeleter>;

// The model exported and loaded by MuJoCo's own compiler (its error in *error).
MjModelPtr Load(const Model& model, std::string* error) {
  const std::string path = testing::ScratchPath("mjcf_export", model.name + ".xml");
  std::ofstream(path) << WriteMjcf(model).mjcf;
  char message[1000] = "";
  MjModelPtr m(mj_loadXML(path.c_str(), nullptr, message, sizeof message));
  *error = message;
  if (m) m->opt.jacobian = mjJAC_DENSE;  // efc_J as a dense matrix, for the ranks below
  return m;
}

Eigen::Vector3d Vec(const mjtNum* v) { return {v[0], v[1], v[2]}; }
Eigen::Matrix3d Mat(const mjtNum* m) {
  Eigen::Matrix3d R;
  R << m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8];
  return R;
}

// The equality rows of d's constraints: their residuals and Jacobian.
void EqualityRows(const mjModel* m, const mjData* d, Eigen::VectorXd* residual, Eigen::MatrixXd* J) {
  std::vector<int> rows;
  for (int i = 0; i < d->nefc; ++i) {
    if (d->efc_type[i] == mjCNSTR_EQUALITY) rows.push_back(i);
  }
  residual->resize(static_cast<Eigen::Index>(rows.size()));
  J->resize(static_cast<Eigen::Index>(rows.size()), m->nv);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    (*residual)[static_cast<Eigen::Index>(r)] = d->efc_pos[rows[r]];
    for (int c = 0; c < m->nv; ++c) (*J)(static_cast<Eigen::Index>(r), c) = d->efc_J[rows[r] * m->nv + c];
  }
}

// The models every check runs on: the bundled ones and three generated.
std::vector<Model> Models() {
  std::vector<Model> models;
  for (const std::string& name : testing::BundledModels()) models.push_back(LoadModel(testing::ModelPath(name)));
  StewartOptions stewart;
  models.push_back(LoadModelFromString(GenerateStewartModel(stewart), "generated_ccma"));
  models.push_back(LoadModelFromString(GenerateStewartGoughModel(stewart), "generated_stewart_gough"));
  LeggedOptions legged;
  legged.agents = 4;
  models.push_back(LoadModelFromString(GenerateLeggedModel(legged), "generated_legged"));
  return models;
}

// The point of a connect's anchor k (0: in body1, 1: in body2) in W.
Eigen::Vector3d Anchor(const mjModel* m, const mjData* d, int eq, int k) {
  const int body = k == 0 ? m->eq_obj1id[eq] : m->eq_obj2id[eq];
  return Vec(d->xpos + 3 * body) + Mat(d->xmat + 9 * body) * Vec(m->eq_data + mjNEQDATA * eq + 3 * k);
}

TEST(MjcfExport, EveryModelLoadsClosedAtQpos0WithCcmasHomeAndMobility) {
  for (const Model& model : Models()) {
    SCOPED_TRACE(model.name);
    std::string error;
    const MjModelPtr m = Load(model, &error);
    ASSERT_TRUE(m) << error;
    EXPECT_EQ(m->nu, model.num_controls());
    const MjDataPtr d(mj_makeData(m.get()));
    mj_resetDataKeyframe(m.get(), d.get(), mj_name2id(m.get(), mjOBJ_KEY, "home"));
    for (int i = 0; i < m->nq; ++i) EXPECT_EQ(d->qpos[i], m->qpos0[i]) << "the home keyframe is qpos0";
    mj_forward(m.get(), d.get());
    Eigen::VectorXd residual;
    Eigen::MatrixXd J;
    EqualityRows(m.get(), d.get(), &residual, &J);
    EXPECT_LT(residual.size() ? residual.cwiseAbs().maxCoeff() : 0.0, 1e-9);
    // Bodies and the end_effector site where ccma puts them at home.
    const State home = State::Home(model);
    for (int b = 0; b < model.num_bodies(); ++b) {
      const int id = mj_name2id(m.get(), mjOBJ_BODY, model.bodies[b].name.c_str());
      ASSERT_GE(id, 0) << model.bodies[b].name;
      EXPECT_LT((Vec(d->xpos + 3 * id) - home.p_WB(b)).norm(), 1e-9) << model.bodies[b].name;
      EXPECT_LT((Mat(d->xmat + 9 * id) - home.R_WB(b)).norm(), 1e-9) << model.bodies[b].name;
    }
    const int site = mj_name2id(m.get(), mjOBJ_SITE, "end_effector");
    ASSERT_GE(site, 0);
    EXPECT_LT((Vec(d->site_xpos + 3 * site) - model.end_effector.p_W_home).norm(), 1e-9);
    // Each connect's two anchors lie on the cut joint (MuJoCo takes the
    // second from qpos0, so the residual alone would not show a misplaced one).
    for (int eq = 0; eq < m->neq; ++eq) {
      if (m->eq_type[eq] != mjEQ_CONNECT) continue;
      const std::string name = mj_id2name(m.get(), mjOBJ_EQUALITY, eq);
      const bool second = name.size() > 2 && name.compare(name.size() - 2, 2, "_2") == 0 && model.FindJoint(name) < 0;
      const int j = model.FindJoint(second ? name.substr(0, name.size() - 2) : name);
      ASSERT_GE(j, 0) << name;
      const Joint& joint = model.joints[j];
      const Eigen::Vector3d point = home.R_WB(joint.body_a) * joint.p_A + home.p_WB(joint.body_a);
      const Eigen::Vector3d on_axis =
          joint.type == JointType::kRevolute
              ? point + kMjcfAnchorSpacing * (home.R_WB(joint.body_a) * joint.a_A).normalized() * (second ? 1.0 : 0.0)
              : point;
      EXPECT_LT((Anchor(m.get(), d.get(), eq, 0) - on_axis).norm(), 1e-9) << name;
      EXPECT_LT((Anchor(m.get(), d.get(), eq, 1) - on_axis).norm(), 1e-9) << name;
    }
    // Mobility: MuJoCo's DOFs less the rank of the equality Jacobian, ccma's
    // with the controls free (ccma's counts its effective controls free; in
    // MuJoCo every control is a joint, a reduced base's heading too).
    const MobilityReport mobility = AnalyzeMobility(model, home, model.home_controls());
    int rank = 0;
    if (J.rows() > 0) {
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J);
      const Eigen::VectorXd& sigma = svd.singularValues();
      while (rank < sigma.size() && sigma[rank] > 1e-8 * std::max(1.0, sigma[0])) ++rank;
    }
    const int ineffective = model.num_controls() - static_cast<int>(model.effective_control_indices().size());
    EXPECT_EQ(m->nv - rank, mobility.dof_with_controls_free + ineffective);
  }
}

// MuJoCo run for `seconds` from the home keyframe, its position actuators
// commanded to u.
void Settle(const mjModel* m, mjData* d, const Eigen::VectorXd& u, double seconds) {
  mj_resetDataKeyframe(m, d, mj_name2id(m, mjOBJ_KEY, "home"));
  for (int i = 0; i < m->nu; ++i) d->ctrl[i] = u[i];
  const int steps = static_cast<int>(std::lround(seconds / m->opt.timestep));
  for (int k = 0; k < steps; ++k) mj_step(m, d);
  mj_forward(m, d);
}

double MaxEqualityResidual(const mjModel* m, const mjData* d) {
  Eigen::VectorXd residual;
  Eigen::MatrixXd J;
  EqualityRows(m, d, &residual, &J);
  return residual.size() ? residual.cwiseAbs().maxCoeff() : 0.0;
}

// Held by its actuators under gravity for 2 s, a model with masses keeps
// its loops closed within 1e-4 m, and the actuator forces settle to ccma
// statics' efforts (tolerances below: what the equalities' softness, the
// actuators' stiffness and the 1 g given to massless bodies explain).
TEST(MjcfExport, HeldUnderGravityTheLoopsStayClosedAndTheEffortsAreCcmas) {
  for (const std::string file : {"tripod.yaml", "stewart_gough_loaded.yaml", "4dof_payload.yaml"}) {
    SCOPED_TRACE(file);
    const Model model = LoadModel(std::string(CCMA_SOURCE_DIR) + "/examples/statics/" + file);
    std::string error;
    const MjModelPtr m = Load(model, &error);
    ASSERT_TRUE(m) << error;
    const MjDataPtr d(mj_makeData(m.get()));
    Settle(m.get(), d.get(), model.home_controls(), 2.0);
    EXPECT_LT(MaxEqualityResidual(m.get(), d.get()), 1e-4);
    // ccma's statics where MuJoCo settled: the actuators sag by effort / kp
    // (1.2 mm on the loaded Stewart's legs), which moves the efforts by up
    // to 0.5 % of the largest; at MuJoCo's own joint positions (each
    // control's qpos) that part is gone, and what is left (0.11 %) is the
    // equalities' softness and the 1 g of each massless body. Over-actuated
    // controls (4dof_payload) settle a little inconsistent, which ccma does
    // not assemble: those are compared at home.
    Eigen::VectorXd settled(m->nu);
    for (int i = 0; i < m->nu; ++i) settled[i] = d->actuator_length[i];
    ForwardProblem forward(model);
    const bool at_settled = forward.Assemble(settled).assembled;
    const double tolerance = at_settled ? 0.002 : 0.01;
    const StaticsReport statics = at_settled ? ComputeStatics(model, forward.state(), forward.controls())
                                             : ComputeStatics(model, State::Home(model), model.home_controls());
    ASSERT_EQ(static_cast<int>(statics.actuators.size()), m->nu);
    double largest = 0;
    for (const ActuatorEffort& a : statics.actuators) largest = std::max(largest, std::abs(a.effort));
    ASSERT_GT(largest, 1.0);
    for (int i = 0; i < m->nu; ++i) {
      EXPECT_NEAR(d->actuator_force[i], statics.actuators[i].effort, tolerance * largest)
          << mj_id2name(m.get(), mjOBJ_ACTUATOR, i);
    }
  }
}

// Driven to other controls (seeded, each assembled by ccma), MuJoCo's
// settled end-effector is where ccma simulate puts it, within 1e-3 m.
TEST(MjcfExport, DrivenToOtherControlsTheEndEffectorSettlesWhereCcmaPutsIt) {
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<double> step(-0.03, 0.03);
  for (const Model& model : Models()) {
    SCOPED_TRACE(model.name);
    std::string error;
    const MjModelPtr m = Load(model, &error);
    ASSERT_TRUE(m) << error;
    const MjDataPtr d(mj_makeData(m.get()));
    // A control near home that ccma assembles (consistent controls: a
    // small move of the end-effector, controlled by ccma).
    ControlProblem control(model);
    const EndEffectorPose home = ComputeEndEffectorPose(model, State::Home(model));
    PoseTarget target;
    target.position = home.position + Eigen::Vector3d{step(rng), step(rng), step(rng)};
    target.rpy = home.rpy;
    ASSERT_TRUE(control.MoveTo(target).assembled);
    ForwardProblem forward(model);
    ASSERT_TRUE(forward.Assemble(control.controls()).assembled);
    Settle(m.get(), d.get(), control.controls(), 2.0);
    const int site = mj_name2id(m.get(), mjOBJ_SITE, "end_effector");
    EXPECT_LT((Vec(d->site_xpos + 3 * site) - forward.end_effector().position).norm(), 1e-3);
    EXPECT_LT(MaxEqualityResidual(m.get(), d.get()), 1e-4);
  }
}

}  // namespace mjcf_export_test
}  // namespace ccma
