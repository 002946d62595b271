// Forward solve (paper Section III-A): the robots stand somewhere, where are
// all the links and the end-effector? ccma finds the configuration s that makes
// every joint constraint hold, i.e. minimises E = 1/2 |C(s, u)|^2 for the
// controls u; "assembled" means E < 1e-16 m^2 (all joints closed).
//
//   build/examples/example_forward_solve [MODEL.yaml]    (default models/4dof_reduced.yaml)
//
// Units everywhere: metres, radians; E in m^2. Prints "example: ok" at the end
// when the mechanism assembled; exit 1 when it did not, 2 for a bad model file.
#include <cmath>
#include <iostream>

#include <ccma/ccma.h>

namespace {

// For printing: values below 1e-9 (m or rad) are rounding noise; show them as 0.
Eigen::VectorXd Tidy(const Eigen::VectorXd& v) {
  return v.unaryExpr([](double x) { return std::abs(x) < 1e-9 ? 0.0 : x; });
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "models/4dof_reduced.yaml";
  try {
    // The model is constant and may be shared by several problems.
    const ccma::Model model = ccma::LoadModel(path);  // throws ccma::ModelError("file:line: key: ...")
    ccma::ForwardProblem forward(model);               // keeps a reference: `model` must outlive it

    // The controls u: per mobile base, in file order: x [m], y [m], theta [rad] (a legged base six);
    // then one per actuated joint (its coordinate q, rad or m). Home = the file's poses.
    Eigen::VectorXd u = model.home_controls();

    // Move the bases a little: each one 1 cm towards the bases' centre. The
    // formation shrinks, so the legs fold and the end-effector rises.
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (int k = 0; k < model.num_bases(); ++k) centre += u.segment<2>(model.base_control(k));
    if (model.num_bases() > 0) centre /= model.num_bases();
    for (int k = 0; k < model.num_bases(); ++k) {
      const Eigen::Vector2d to_centre = centre - u.segment<2>(model.base_control(k));
      if (to_centre.norm() > 0) u.segment<2>(model.base_control(k)) += 0.01 * to_centre.normalized();
    }
    // Motors (models such as stewart_gough_6ups have no bases): +0.01 rad or m each.
    for (const ccma::Joint& j : model.joints) {
      if (j.actuated) u[j.control] += 0.01;
    }

    // Assemble() walks from the current controls to u in sub-steps of at most
    // 2 cm / 0.02 rad, warm-starting each solve, so it stays on the assembly
    // branch connected to home. (Solve(u) does one warm-started solve.)
    const ccma::ForwardResult r = forward.Assemble(u);
    std::cout << std::boolalpha << "assembled " << r.assembled << ", E = " << r.residual_energy << " m^2, "
              << r.iterations << " iterations in " << r.substeps << " sub-steps, " << r.solve_time_ms << " ms\n";

    // The end-effector: the model's `end_effector.point`; rpy is its rotation since home.
    const ccma::EndEffectorPose ee = forward.end_effector();
    std::cout << "end-effector p_WE = [" << Tidy(ee.position).transpose() << "] m (moved by ["
              << Tidy(ee.position - model.end_effector.p_W_home).transpose() << "] m), rpy = ["
              << Tidy(ee.rpy).transpose() << "] rad\n";

    // Body poses: position p_WB [m] and orientation R_WB of each body's frame
    // (file order: `bodies` first, then the mobile bases). The first three:
    for (int b = 0; b < model.num_bodies() && b < 3; ++b) {
      std::cout << "body " << model.bodies[b].name << ": p_WB = [" << Tidy(forward.state().p_WB(b)).transpose()
                << "] m, rpy = [" << Tidy(ccma::RpyFromRotation(forward.state().R_WB(b))).transpose() << "] rad\n";
    }
    // Joint coordinates q (0 at home): the angle of a revolute joint [rad], the
    // travel of a prismatic one [m]; other joint types have none.
    for (const ccma::JointCoordinateReport& j : ccma::JointCoordinates(model, forward.state())) {
      const ccma::Joint& joint = model.joints[j.joint];
      const bool prismatic = joint.type == ccma::JointType::kPrismatic;
      std::cout << "joint " << joint.name << ": q = " << (std::abs(j.q) < 1e-9 ? 0.0 : j.q)
                << (prismatic ? " m" : " rad") << "\n";
    }

    if (!r.assembled) {
      // Not a crash: the solver reports the closest configuration it found. A
      // mechanism with fewer end-effector DOF than controls (`ccma check`)
      // cannot follow every base motion; 4dof_complete and hybrid_ccma cannot
      // follow this one.
      std::cerr << "example: not assembled (E = " << r.residual_energy
                << " m^2): these controls are not reachable for " << model.name << "\n";
      return 1;
    }
    std::cout << "example: ok\n";
  } catch (const ccma::ModelError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {  // e.g. std::invalid_argument for inputs out of range
    std::cerr << "example: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
