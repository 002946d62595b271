// Control step: find controls that move the end-effector 3 cm up and 2 cm
// along y, then look at the sensitivities the solver used.
//   build/examples/example_control_step models/4dof_reduced.yaml
// Prints "example: ok" when the target was reached (exit 1 otherwise).
#include <iostream>

#include <ccma/ccma.h>

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "models/4dof_reduced.yaml";
  try {
    const ccma::Model model = ccma::LoadModel(path);
    ccma::ControlProblem control(model);  // LM outer loop, implicit-function gradients

    // The target: components the model does not control are ignored.
    ccma::PoseTarget target = control.CurrentPose();
    target.position.y() += 0.02;  // m
    target.position.z() += 0.03;  // m
    // MoveTo walks there in paper-size steps (10 mm, 0.005 rad), each warm-started.
    const ccma::ControlResult r = control.MoveTo(target);
    std::cout << "converged " << r.converged << " in " << r.steps << " steps, " << r.iterations
              << " iterations; error " << r.error << " m; E = " << r.residual_energy << " m^2\n";
    std::cout << "controls: [" << control.controls().transpose() << "]\n";

    // ds/du: how the state moves per unit of each effective control; the
    // end-effector Jacobian dX/du = dX/ds ds/du (rows x y z [m], then the
    // rotation increment [rad]) is what the control step inverts.
    const Eigen::MatrixXd ds_du = control.StateSensitivity();
    const Eigen::MatrixXd dX_du = ccma::EndEffectorJacobian(model, control.forward().state()) * ds_du;
    std::cout << "ds/du: " << ds_du.rows() << " x " << ds_du.cols() << "\n";
    std::cout << "dX/du (position rows):\n" << dX_du.topRows(3) << "\n";
    if (!r.converged) {
      std::cerr << "example: " << r.warning << "\n";
      return 1;
    }
    std::cout << "example: ok\n";
  } catch (const ccma::ModelError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
  return 0;
}
