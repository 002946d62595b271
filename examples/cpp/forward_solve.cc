// Forward solve: load a model, move its bases a little, assemble the
// mechanism there and print what a simulation loop would read.
//   build/examples/example_forward_solve models/4dof_reduced.yaml
// Prints "example: ok" when the mechanism assembled (exit 1 otherwise).
#include <iostream>

#include <ccma/ccma.h>

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "models/4dof_reduced.yaml";
  try {
    const ccma::Model model = ccma::LoadModel(path);  // constant, shared by every problem
    ccma::ForwardProblem forward(model);               // keeps a reference to `model`

    // Controls: 3 per mobile base (x [m], y [m], theta [rad]), then one per
    // actuated joint. Translating every base by the same amount moves the
    // whole mechanism rigidly, so these controls are reachable for any model.
    Eigen::VectorXd u = model.home_controls();
    for (int k = 0; k < model.num_bases(); ++k) {
      u[ccma::kBaseControlSize * k + 0] += 0.02;   // +2 cm along x
      u[ccma::kBaseControlSize * k + 1] -= 0.01;   // -1 cm along y
    }
    // Assemble walks the controls there in small sub-steps (stays on the branch).
    const ccma::ForwardResult r = forward.Assemble(u);
    std::cout << "assembled " << r.assembled << ", E = " << r.residual_energy << " m^2, " << r.iterations
              << " iterations, " << r.solve_time_ms << " ms\n";

    const ccma::EndEffectorPose ee = forward.end_effector();
    std::cout << "end-effector p_WE = [" << ee.position.transpose() << "] m, rpy = [" << ee.rpy.transpose()
              << "] rad\n";
    // Body poses: p_WB and R_WB of each body (the first three).
    for (int b = 0; b < model.num_bodies() && b < 3; ++b) {
      std::cout << "body " << model.bodies[b].name << ": p_WB = [" << forward.state().p_WB(b).transpose()
                << "] m\n";
    }
    // Joint coordinates q of revolute [rad] and prismatic [m] joints.
    for (const ccma::JointCoordinateReport& j : ccma::JointCoordinates(model, forward.state())) {
      std::cout << "joint " << model.joints[j.joint].name << ": q = " << j.q << "\n";
    }
    if (!r.assembled) {
      std::cerr << "example: not assembled\n";
      return 1;
    }
    std::cout << "example: ok\n";
  } catch (const ccma::ModelError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
  return 0;
}
