// A closed-loop mechanism in MuJoCo (docs/import.md, "MuJoCo (MJCF)"): ccma
// writes the model as MJCF, at its assembled home with the loops as equality
// constraints; MuJoCo loads it and its position actuators drive the controls
// that ccma's controller finds for an end-effector target 2 cm higher. The
// loops stay closed, and MuJoCo's end-effector ends where ccma's does.
//
//   build/examples/example_mujoco_run [MODEL.yaml] [OUT.xml]
//       (default models/4dof_reduced.yaml, mujoco_run.xml)
//
// Units: metres, radians, seconds. Prints "example: ok" at the end when
// MuJoCo's end-effector settles within 1 mm of ccma's and every loop holds
// within 0.1 mm; exit 1 when not, 2 for a bad model file.
#include <cmath>
#include <fstream>
#include <iostream>

#include <mujoco/mujoco.h>

#include <ccma/ccma.h>
#include "formats/mjcf_writer.h"

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "models/4dof_reduced.yaml";
  const std::string out = argc > 2 ? argv[2] : "mujoco_run.xml";
  try {
    const ccma::Model model = ccma::LoadModel(path);
    std::ofstream(out) << ccma::WriteMjcf(model).mjcf;  // what `ccma export --format=mjcf` writes

    char error[1000] = "";
    mjModel* m = mj_loadXML(out.c_str(), nullptr, error, sizeof error);
    if (m == nullptr) {
      std::cerr << "MuJoCo refused " << out << ": " << error << "\n";
      return 1;
    }
    mjData* d = mj_makeData(m);
    mj_resetDataKeyframe(m, d, mj_name2id(m, mjOBJ_KEY, "home"));  // the assembled home

    // ccma: the controls that lift the end-effector by 2 cm, and where that puts it.
    ccma::ControlProblem control(model);
    ccma::PoseTarget target;
    const ccma::EndEffectorPose home = ccma::ComputeEndEffectorPose(model, ccma::State::Home(model));
    target.position = home.position + Eigen::Vector3d(0, 0, 0.02);
    target.rpy = home.rpy;
    const Eigen::VectorXd u = control.MoveTo(target).assembled ? control.controls() : model.home_controls();
    ccma::ForwardProblem forward(model);
    forward.Assemble(u);

    // MuJoCo: the actuators' commands moved from home to u over 1 s, then held for 1 s.
    const Eigen::VectorXd u0 = model.home_controls();
    const int site = mj_name2id(m, mjOBJ_SITE, "end_effector");
    double worst_loop = 0;
    for (int step = 0; step < 2000; ++step) {
      const double s = std::min(1.0, step * m->opt.timestep);
      for (int i = 0; i < m->nu; ++i) d->ctrl[i] = u0[i] + s * (u[i] - u0[i]);
      mj_step(m, d);
      for (int i = 0; i < d->nefc; ++i) {
        if (d->efc_type[i] == mjCNSTR_EQUALITY) worst_loop = std::max(worst_loop, std::abs(d->efc_pos[i]));
      }
    }
    mj_forward(m, d);
    const Eigen::Vector3d p_mujoco(d->site_xpos[3 * site], d->site_xpos[3 * site + 1], d->site_xpos[3 * site + 2]);
    const double miss = (p_mujoco - forward.end_effector().position).norm();
    std::cout << "wrote " << out << " (" << m->nbody - 1 << " bodies, " << m->neq << " equalities, " << m->nu
              << " actuators)\n"
              << "end-effector: ccma " << forward.end_effector().position.transpose() << ", MuJoCo "
              << p_mujoco.transpose() << " (" << miss * 1e3 << " mm apart)\n"
              << "largest loop residual in MuJoCo while it moved: " << worst_loop * 1e3 << " mm\n";
    mj_deleteData(d);
    mj_deleteModel(m);
    if (miss > 1e-3 || worst_loop > 1e-4) return 1;
    std::cout << "example: ok\n";
    return 0;
  } catch (const ccma::ModelError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
}
