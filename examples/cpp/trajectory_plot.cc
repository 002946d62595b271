// Trajectory with a plot: follow the paper's sequential path on 4dof_reduced,
// write one CSV row per control step, and plot the end-effector's targets and
// reached positions over time with gnuplot.
//   build/examples/example_trajectory_plot models/4dof_reduced.yaml \
//       models/paths/4dof_sequential.csv OUT_DIR
// Writes OUT_DIR/trajectory.csv and OUT_DIR/trajectory.png; prints
// "example: ok" when every waypoint was reached.
#include <spawn.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <vector>

#include <ccma/ccma.h>

extern char** environ;

namespace {

// gnuplot reads the file names as arguments (-c SCRIPT ARG1 ARG2): nothing
// from the command line is pasted into a script or a shell command.
const char* kPlotScript = R"(set datafile separator ','
set terminal pngcairo size 1000,700
set output ARG2
set multiplot layout 3,1 title 'ccma: end-effector along the 4-DOF sequential path (target dashed, reached solid)'
set key right top
set grid
do for [i=1:3] {
  c = word("x y z", i)
  set ylabel sprintf('%s [m]', c)
  if (i == 3) {
    set xlabel 'time [s]'
  }
  plot ARG1 using 1:(column(1+i)) every ::1 with lines dt 2 lw 2 title 'target '.c, \
       ARG1 using 1:(column(4+i)) every ::1 with lines lw 1 title 'reached '.c
}
unset multiplot
)";

// 0: plotted; 1: gnuplot is not installed; 2: gnuplot failed.
int RunGnuplot(const std::string& script, const std::string& csv, const std::string& png) {
  std::vector<std::string> args = {"gnuplot", "-c", script, csv, png};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, "gnuplot", nullptr, nullptr, argv.data(), environ) != 0) return 1;
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: example_trajectory_plot MODEL.yaml WAYPOINTS.csv OUT_DIR\n";
    return 2;
  }
  try {
    const ccma::Model model = ccma::LoadModel(argv[1]);
    const std::vector<ccma::Waypoint> waypoints = ccma::LoadWaypoints(argv[2]);
    const std::filesystem::path dir = argv[3];
    std::filesystem::create_directories(dir);
    const std::string csv_path = (dir / "trajectory.csv").string();
    std::ofstream csv(csv_path);
    csv.precision(12);
    csv << "time_s,target_x_m,target_y_m,target_z_m,x_m,y_m,z_m\n";

    ccma::ControlProblem control(model);
    const ccma::TrajectoryResult r = ccma::FollowWaypoints(control, waypoints, [&](const ccma::TrajectoryStep& s) {
      csv << s.time << "," << s.target.position.x() << "," << s.target.position.y() << ","
          << s.target.position.z() << "," << s.reached.position.x() << "," << s.reached.position.y() << ","
          << s.reached.position.z() << "\n";
    });
    csv.close();
    std::cout << "converged " << r.converged << ": " << r.steps << " steps, max error " << r.max_error
              << " m, max E " << r.max_residual_energy << " m^2, " << r.solve_time_ms << " ms\n";
    std::cout << "wrote " << csv_path << "\n";

    const std::string script = (dir / "trajectory.gnuplot").string();
    std::ofstream(script) << kPlotScript;
    const std::string png = (dir / "trajectory.png").string();
    const int plotted = RunGnuplot(script, csv_path, png);
    if (plotted == 0) {
      std::cout << "wrote " << png << "\n";
    } else if (plotted == 1) {
      std::cerr << "example: gnuplot not found: plot skipped (apt-get install gnuplot-nox)\n";
    } else {
      std::cerr << "example: gnuplot failed on " << script << "\n";
      return 1;
    }
    if (!r.converged) {
      std::cerr << "example: " << r.warning << "\n";
      return 1;
    }
    std::cout << "example: ok\n";
  } catch (const std::exception& e) {  // ModelError, WaypointError
    std::cerr << e.what() << "\n";
    return 2;
  }
  return 0;
}
