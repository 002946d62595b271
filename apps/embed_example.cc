// Embedding ccma: load a model, build the forward problem once and re-solve
// it warm-started as the bases move (what a simulation loop does), then ask
// the control problem for the controls that move the end-effector.
//   build/apps/embed_example models/4dof_reduced.yaml
#include <iostream>

#include <ccma/ccma.h>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: embed_example MODEL.yaml\n";
    return 2;
  }
  try {
    const ccma::Model model = ccma::LoadModel(argv[1]);  // shared, read-only
    // 1. Forward: drive every base 2 mm along x, five times. The whole
    //    mechanism translates, so these controls are reachable for any model.
    ccma::ForwardProblem forward(model);  // keeps a reference to `model`
    Eigen::VectorXd u = model.home_controls();  // [x0, y0, theta0, x1, ...]
    bool assembled = true;
    for (int step = 1; step <= 5; ++step) {
      for (int k = 0; k < model.num_bases(); ++k) u[model.base_control(k)] += 0.002;
      const ccma::ForwardResult r = forward.Solve(u);
      const Eigen::Vector3d p_WE = forward.end_effector().position;
      std::cout << "step " << step << ": assembled=" << r.assembled << " E=" << r.residual_energy
                << " iterations=" << r.iterations << " ee=[" << p_WE.transpose() << "]\n";
      assembled = assembled && r.assembled;
    }
    // 2. Control: the end-effector 1 cm up from home (in paper-size steps).
    ccma::ControlProblem control(model);
    ccma::PoseTarget target = control.CurrentPose();
    target.position.z() += 0.01;
    const ccma::ControlResult c = control.MoveTo(target);
    std::cout << "control: converged=" << c.converged << " steps=" << c.steps << " error=" << c.error
              << " controls=[" << control.controls().transpose() << "]\n";
    if (!c.warning.empty()) std::cerr << "warning: " << c.warning << "\n";
    std::cout << "summary: assembled=" << assembled << " converged=" << c.converged << "\n";
  } catch (const ccma::ModelError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
  return 0;
}
