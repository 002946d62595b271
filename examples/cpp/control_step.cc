// Control step (paper Section III-B): the inverse question. Where must the
// robots go so that the end-effector reaches a target? ccma minimises
// 1/2 |X_EE(u) - X*|^2 + lambda E over the effective controls u, with
// gradients from the implicit-function sensitivities ds/du.
//
//   build/examples/example_control_step [MODEL.yaml]    (default models/4dof_reduced.yaml)
//
// Units: metres and radians. Prints "example: ok" at the end when the target
// was reached; exit 1 when it was not, 2 for a bad model file.
#include <cmath>
#include <iomanip>
#include <iostream>

#include <ccma/ccma.h>

namespace {

// For printing: rounded to `digits` decimals, -0 shown as 0.
Eigen::MatrixXd Rounded(const Eigen::MatrixXd& m, int digits) {
  const double scale = std::pow(10.0, digits);
  return ((m.array() * scale).round() / scale + 0.0).matrix();
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "models/4dof_reduced.yaml";
  try {
    const ccma::Model model = ccma::LoadModel(path);
    ccma::ControlProblem control(model);  // starts assembled at home; default options (LM)

    // The target: the current pose [x y z m, roll pitch yaw rad] moved 2 cm
    // along y and 3 cm up. Only the components listed in the model's
    // `end_effector.controlled` are aimed at; the others are left to follow.
    ccma::PoseTarget target = control.CurrentPose();
    target.position.y() += 0.02;
    target.position.z() += 0.03;

    // MoveTo walks there in paper-size steps (at most 10 mm and 0.005 rad
    // each), each step warm-started from the last.
    const ccma::ControlResult r = control.MoveTo(target);
    std::cout << std::boolalpha << "converged " << r.converged << " in " << r.steps << " steps, "
              << r.iterations << " iterations; error " << r.error << " m; E = " << r.residual_energy << " m^2\n";
    // The controls found: 3 per base [x m, y m, theta rad], then the motors.
    std::cout << std::fixed << std::setprecision(6) << "controls: ["
              << Rounded(control.controls().transpose(), 6) << "]\n";

    // The sensitivities at the solution. Their columns are the *effective*
    // controls: those the solver may change (a `reduced` base keeps its theta).
    const std::vector<int> effective = model.effective_control_indices();
    std::cout << "effective controls (indices into the controls):";
    for (int i : effective) std::cout << " " << i;
    std::cout << "\n";
    // ds/du: how the state (6 per body: rotation [rad], translation [m]) moves
    // per unit of each effective control.
    const Eigen::MatrixXd ds_du = control.StateSensitivity();
    // dX/du = dX/ds * ds/du: how the end-effector moves per unit of each
    // effective control; rows x y z [m], then the rotation increment [rad].
    // This is the Jacobian the control step inverts.
    const Eigen::MatrixXd dX_du = ccma::EndEffectorJacobian(model, control.forward().state()) * ds_du;
    std::cout << "ds/du: " << ds_du.rows() << " x " << ds_du.cols() << " (state size " << model.state_size()
              << " x effective controls " << effective.size() << ")\n";
    std::cout << "dX/du: " << dX_du.rows() << " x " << dX_du.cols() << " (rows x y z [m/unit], rx ry rz [rad/unit])\n"
              << std::setprecision(4) << Rounded(dX_du, 4) << "\n";

    // The example's own checks: target reached, sensitivities of the right shape.
    if (!r.converged) {
      std::cerr << "example: target not reached: " << r.warning << "\n";
      return 1;
    }
    if (ds_du.rows() != model.state_size() || ds_du.cols() != static_cast<int>(effective.size()) ||
        dX_du.rows() != 6 || !dX_du.allFinite()) {
      std::cerr << "example: unexpected sensitivity shapes\n";
      return 1;
    }
    std::cout << "example: ok\n";
  } catch (const ccma::ModelError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {  // e.g. std::invalid_argument for a target out of range
    std::cerr << "example: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
