// Trajectory with a plot: follow a waypoint file (by default the paper's
// sequential path, its Fig. 7: y, z, x, then yaw, out and back), write one CSV
// row per control step, and plot targets, reached poses and the bases' paths
// with gnuplot.
//
//   build/examples/example_trajectory_plot [MODEL.yaml WAYPOINTS.csv [OUT_DIR]]
//
// Defaults: models/4dof_reduced.yaml, models/paths/4dof_sequential.csv,
// trajectory_out/. Writes OUT_DIR/trajectory.csv, and OUT_DIR/trajectory.png
// when gnuplot is installed (the script, OUT_DIR/trajectory.gnuplot, is kept).
// Units: s, m, rad. Prints "example: ok" at the end when every waypoint was
// reached and the CSV written; exit 1 otherwise, 2 for bad input files.
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <vector>

#include <ccma/ccma.h>

extern char** environ;

namespace {

// The CSV's columns (1-based, as gnuplot counts them): 1 time [s]; 2-5 target
// x y z [m], yaw [rad]; 6-9 reached x y z [m], yaw [rad]; then x y [m] of each
// base k = 1, 2, ... in columns 8+2k and 9+2k.
// gnuplot receives the file names, the bases' names and the title as
// arguments (gnuplot -c SCRIPT ARG1 ARG2 ARG3 ARG4): nothing is pasted into
// the script, and no shell is involved.
const char* kPlotScript = R"(# ARG1 CSV, ARG2 PNG, ARG3 the bases' names (one word each), ARG4 title
set datafile separator ','
set terminal pngcairo size 1300,800 font 'sans,10' noenhanced
set output ARG2
set multiplot title ARG4 font ',12'
set grid lc rgb '#d0d0d0'
set key top right font ',8' opaque
# Left column, the end-effector over time: target dashed, reached solid;
# 30 % headroom above the curves for the legend.
set offsets 0, 0, graph 0.3, graph 0.05
set lmargin at screen 0.07
set rmargin at screen 0.58
set tmargin at screen 0.90
set bmargin at screen 0.67
set title 'end-effector: target (dashed) and reached (solid)'
set ylabel 'end-effector x, y [m]'
plot ARG1 every ::1 using 1:2 with lines dt 2 lw 4 lc rgb '#801f77b4' title 'target x', \
     ''   every ::1 using 1:6 with lines lw 1 lc rgb '#1f77b4' title 'reached x', \
     ''   every ::1 using 1:3 with lines dt 2 lw 4 lc rgb '#80ff7f0e' title 'target y', \
     ''   every ::1 using 1:7 with lines lw 1 lc rgb '#ff7f0e' title 'reached y'
unset title
set tmargin at screen 0.62
set bmargin at screen 0.39
set ylabel 'end-effector z [m]'
plot ARG1 every ::1 using 1:4 with lines dt 2 lw 4 lc rgb '#802ca02c' title 'target z', \
     ''   every ::1 using 1:8 with lines lw 1 lc rgb '#2ca02c' title 'reached z'
set tmargin at screen 0.34
set bmargin at screen 0.10
set xlabel 'time [s]'
set ylabel 'end-effector yaw [rad]'
plot ARG1 every ::1 using 1:5 with lines dt 2 lw 4 lc rgb '#809467bd' title 'target yaw', \
     ''   every ::1 using 1:9 with lines lw 1 lc rgb '#9467bd' title 'reached yaw'
# Right: seen from above, the bases' paths on the ground (circle: start)
# and the end-effector's path, with equal scales on x and y.
set lmargin at screen 0.66
set rmargin at screen 0.97
set tmargin at screen 0.90
set bmargin at screen 0.10
set size ratio -1
set offsets 0.05, 0.05, graph 0.3, 0.05
set title 'seen from above (circle: start)'
set xlabel 'x [m]'
set ylabel 'y [m]'
n = words(ARG3)
plot for [k=1:n] ARG1 every ::1 using (column(8+2*k)):(column(9+2*k)) with lines lw 2 lc k title word(ARG3, k), \
     for [k=1:n] ''   every ::1::1 using (column(8+2*k)):(column(9+2*k)) with points pt 6 ps 2 lc k notitle, \
     ''   every ::1 using 2:3 with lines dt 2 lw 4 lc rgb '#80000000' title 'end-effector target', \
     ''   every ::1 using 6:7 with lines lw 1 lc rgb '#000000' title 'end-effector reached'
unset multiplot
)";

// Runs gnuplot with an argument vector (posix_spawnp searches PATH; no shell).
// 0: plotted; 1: gnuplot is not installed; 2: gnuplot failed.
int RunGnuplot(std::vector<std::string> args) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawn_error = posix_spawnp(&pid, "gnuplot", nullptr, nullptr, argv.data(), environ);
  if (spawn_error == ENOENT) return 1;
  if (spawn_error != 0) return 2;
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return 2;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 1 && argc != 3 && argc != 4) {
    std::cerr << "usage: example_trajectory_plot [MODEL.yaml WAYPOINTS.csv [OUT_DIR]]\n";
    return 2;
  }
  const std::string model_path = argc > 1 ? argv[1] : "models/4dof_reduced.yaml";
  const std::string waypoints_path = argc > 2 ? argv[2] : "models/paths/4dof_sequential.csv";
  const std::filesystem::path dir = argc > 3 ? argv[3] : "trajectory_out";
  try {
    const ccma::Model model = ccma::LoadModel(model_path);
    // Waypoints: rows time [s], x y z [m], roll pitch yaw [rad] (docs/waypoints.md).
    const std::vector<ccma::Waypoint> waypoints = ccma::LoadWaypoints(waypoints_path);

    std::filesystem::create_directories(dir);
    const std::string csv_path = (dir / "trajectory.csv").string();
    std::ofstream csv(csv_path);
    csv.precision(12);
    csv << "time_s,target_x_m,target_y_m,target_z_m,target_yaw_rad,x_m,y_m,z_m,yaw_rad";
    std::string base_names;  // for the plot's legend
    for (const ccma::MobileBase& b : model.mobile_bases) {
      csv << "," << b.name << "_x_m," << b.name << "_y_m";
      base_names += (base_names.empty() ? "" : " ") + b.name;  // names never contain spaces
    }
    csv << "\n";

    // FollowWaypoints walks from waypoint to waypoint in small control steps
    // (10 mm, 0.005 rad) and calls us back after each one with its result.
    ccma::ControlProblem control(model);
    int rows = 0;
    const ccma::TrajectoryResult r = ccma::FollowWaypoints(control, waypoints, [&](const ccma::TrajectoryStep& s) {
      csv << s.time;
      for (int i = 0; i < 3; ++i) csv << "," << s.target.position[i];
      csv << "," << s.target.rpy.z();
      for (int i = 0; i < 3; ++i) csv << "," << s.reached.position[i];
      csv << "," << s.reached.rpy.z();
      // Each base's x and y are its first two controls.
      for (int k = 0; k < model.num_bases(); ++k) {
        csv << "," << s.controls[model.base_control(k)] << "," << s.controls[model.base_control(k) + 1];
      }
      csv << "\n";
      ++rows;
    });
    csv.close();
    std::cout << std::boolalpha << "converged " << r.converged << ": " << r.steps << " steps, max error "
              << r.max_error << " m, max E " << r.max_residual_energy << " m^2, " << r.solve_time_ms << " ms\n";
    if (!csv) {
      std::cerr << "example: could not write " << csv_path << "\n";
      return 1;
    }
    std::cout << "wrote " << csv_path << " (" << rows << " rows)\n";

    const std::string script = (dir / "trajectory.gnuplot").string();
    std::ofstream(script) << kPlotScript;
    const std::string png = (dir / "trajectory.png").string();
    const std::string title = model.name + " following " + std::filesystem::path(waypoints_path).filename().string() +
                              ": " + std::to_string(r.steps) + " control steps";
    const int plotted = RunGnuplot({"gnuplot", "-c", script, csv_path, png, base_names, title});
    if (plotted == 0) {
      std::cout << "wrote " << png << "\n";
    } else if (plotted == 1) {
      std::cerr << "example: gnuplot is not installed: plot skipped (apt-get install gnuplot-nox; the script "
                << script << " takes: gnuplot -c SCRIPT CSV PNG 'BASE NAMES' TITLE)\n";
    } else {
      std::cerr << "example: gnuplot failed on " << script << "\n";
      return 1;
    }

    // The example's own checks: every waypoint reached, one CSV row per step.
    if (!r.converged) {
      std::cerr << "example: not every waypoint reached: " << r.warning << "\n";
      return 1;
    }
    if (rows != r.steps) {
      std::cerr << "example: " << rows << " CSV rows for " << r.steps << " steps\n";
      return 1;
    }
    std::cout << "example: ok\n";
  } catch (const ccma::ModelError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const ccma::WaypointError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {  // e.g. the output directory cannot be created
    std::cerr << "example: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
