// Embedding ccma: load a model, build the forward problem once, and re-solve
// it warm-started as the bases move (what a control loop does).
//   build/apps/embed_example models/4dof_reduced.yaml
#include <iostream>

#include <ccma/ccma.h>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: embed_example MODEL.yaml\n";
    return 2;
  }
  try {
    const ccma::Model model = ccma::LoadModel(argv[1]);
    ccma::ForwardProblem forward(model);
    Eigen::VectorXd u = model.home_controls();  // [x0, y0, theta0, x1, ...]
    for (int step = 1; step <= 5; ++step) {
      // Drive every base 2 mm along x: the whole mechanism translates, so
      // these controls are reachable for any model (over-actuated ones too).
      for (int k = 0; k < model.num_bases(); ++k) u[3 * k] += 0.002;
      const ccma::ForwardResult r = forward.Solve(u);
      const Eigen::Vector3d p_WE = forward.end_effector().position;
      std::cout << "step " << step << ": assembled=" << r.assembled
                << " E=" << r.residual_energy << " iterations=" << r.iterations
                << " ee=[" << p_WE.transpose() << "]\n";
    }
  } catch (const ccma::ModelError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
  return 0;
}
