// `ccma replay --model=FILE --waypoints=FILE.csv --out=DIR [--noise=default|none]
//  [--seed=1] [--mocap_noise_m] [--mocap_noise_rad] [--latency_s] [--slip]`:
// the paper's closed loop, simulated (problems/replay.h). Writes
// DIR/end_effector.csv, DIR/bases.csv, DIR/rmse.md and, with gnuplot,
// DIR/end_effector.{png,svg} and DIR/bases_xy.{png,svg}.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/json_output.h"

DECLARE_string(model);
DECLARE_string(waypoints);
DECLARE_string(out);
DECLARE_int32(seed);
DEFINE_string(noise, "default", "replay: 'default' (documented simulated imperfections) or 'none'");
DEFINE_double(mocap_noise_m, -1, "replay: motion-capture noise sigma on x, y [m] (overrides --noise)");
DEFINE_double(mocap_noise_rad, -1, "replay: motion-capture noise sigma on heading [rad]");
DEFINE_double(latency_s, -1, "replay: motion-capture and radio latency [s]");
DEFINE_double(slip, -1, "replay: mean wheel slip, fraction of wheel speed lost");
DEFINE_double(kp, 4.0, "replay: PI proportional gain, position and heading [1/s]");
DEFINE_double(ki, 4.0, "replay: PI integral gain, position and heading [1/s^2]");
DEFINE_double(controller_hz, 100.0, "replay: PI controller rate [Hz]");
DEFINE_double(max_wheel_speed, 30.0, "replay: wheel-speed saturation [rad/s]");

namespace ccma::cli {
namespace {

// The paper's hardware RMSE (Section IV), in its plots' order y, z, x, yaw.
const char* kPaperFigures[][5] = {
    {"reduced scheme, sequential (Fig. 7)", "18", "12", "17", "0.09"},
    {"reduced scheme, combined (Fig. 10)", "18", "22", "24", "0.13"},
    {"complete scheme, combined", "10", "17", "13", "0.10"}};

std::string Fixed(double v, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

}  // namespace

int RunReplay(const std::vector<std::string>& args) {
  std::set<std::string> allowed = kControlFlags;
  for (const char* f : {"waypoints", "out", "noise", "seed", "mocap_noise_m", "mocap_noise_rad", "latency_s", "slip",
                        "kp", "ki", "controller_hz", "max_wheel_speed"}) {
    allowed.insert(f);
  }
  ParseFlags(args, allowed, "replay");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "replay"));
  const std::vector<Waypoint> waypoints = WaypointsFlag("replay");
  const std::string dir = RequireFlag(FLAGS_out, "out", "replay");
  ReplayOptions options;
  options.control = ControlOptionsFromFlags();
  if (FLAGS_noise == "none") {
    options.noise = SimulationNoise::None();
  } else if (FLAGS_noise != "default") {
    throw UsageError("ccma replay: --noise must be 'default' or 'none'");
  }
  if (FLAGS_mocap_noise_m >= 0) options.noise.position_sigma = FLAGS_mocap_noise_m;
  if (FLAGS_mocap_noise_rad >= 0) options.noise.heading_sigma = FLAGS_mocap_noise_rad;
  if (FLAGS_latency_s >= 0) options.noise.mocap_latency = options.noise.command_latency = FLAGS_latency_s;
  if (FLAGS_slip >= 0) {
    if (FLAGS_slip >= 1) throw UsageError("ccma replay: --slip must be below 1");
    options.noise.slip = FLAGS_slip;
  }
  if (FLAGS_seed < 0) throw UsageError("ccma replay: --seed must not be negative");
  if (!(FLAGS_kp > 0) || !(FLAGS_ki >= 0) || !(FLAGS_controller_hz > 0) || !(FLAGS_max_wheel_speed > 0) ||
      FLAGS_controller_hz > 10000) {
    throw UsageError("ccma replay: --kp, --controller_hz (<= 10000) and --max_wheel_speed must be positive, --ki >= 0");
  }
  options.gains.kp_position = options.gains.kp_heading = FLAGS_kp;
  options.gains.ki_position = options.gains.ki_heading = FLAGS_ki;
  options.gains.rate_hz = FLAGS_controller_hz;
  options.gains.max_wheel_speed = FLAGS_max_wheel_speed;
  options.noise.seed = static_cast<unsigned>(FLAGS_seed);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) throw UsageError("ccma replay: --out: cannot create '" + dir + "'");

  const ReplayResult r = Replay(model, waypoints, options);
  const SimulationNoise& n = options.noise;
  const nlohmann::json noise = {{"mocap_position_sigma_m", n.position_sigma}, {"mocap_heading_sigma_rad", n.heading_sigma},
                                {"mocap_latency_s", n.mocap_latency},        {"mocap_hz", n.mocap_hz},
                                {"command_latency_s", n.command_latency},   {"slip", n.slip},
                                {"slip_sigma", n.slip_sigma},               {"seed", n.seed}};
  const nlohmann::json controller = {{"kp", options.gains.kp_position}, {"ki", options.gains.ki_position},
                                     {"rate_hz", options.gains.rate_hz},
                                     {"max_wheel_speed", options.gains.max_wheel_speed},
                                     {"velocity_feedforward", options.gains.velocity_feedforward}};

  // CSV files, labelled as simulation.
  {
    std::ofstream ee(dir + "/end_effector.csv");
    ee << "# SIMULATION (ccma replay): commanded = control solution, tracked = chain on the driven bases\n"
       << "time,cmd_x,cmd_y,cmd_z,cmd_roll,cmd_pitch,cmd_yaw,x,y,z,roll,pitch,yaw,residual_energy\n"
       << std::setprecision(12);
    std::ofstream bases(dir + "/bases.csv");
    bases << "# SIMULATION (ccma replay): set and true poses of every base\ntime";
    for (int k = 0; k < model.num_bases(); ++k) {
      bases << ",set" << k << "_x,set" << k << "_y,set" << k << "_theta,base" << k << "_x,base" << k << "_y,base" << k << "_theta";
    }
    bases << "\n" << std::setprecision(12);
    for (const ReplaySample& s : r.samples) {
      ee << s.time;
      for (int c = 0; c < 6; ++c) ee << "," << s.commanded[c];
      for (int c = 0; c < 6; ++c) ee << "," << s.tracked[c];
      ee << "," << s.residual_energy << "\n";
      bases << s.time;
      for (int k = 0; k < model.num_bases(); ++k) {
        for (int c = 0; c < 3; ++c) bases << "," << s.set_controls[3 * k + c];
        for (int c = 0; c < 3; ++c) bases << "," << s.true_controls[3 * k + c];
      }
      bases << "\n";
    }
  }
  // The RMSE table next to the paper's hardware figures.
  std::ostringstream table;
  table << "RMSE of the end-effector, tracked against commanded. ccma: SIMULATION of " << model.name
        << " on " << std::filesystem::path(FLAGS_waypoints).filename().string() << " (noise: "
        << FLAGS_noise << ", mocap " << n.position_sigma * 1000 << " mm / " << n.heading_sigma << " rad, latency "
        << n.mocap_latency * 1000 << "+" << n.command_latency * 1000 << " ms, slip " << n.slip * 100 << " +- "
        << n.slip_sigma * 100 << " %, seed " << n.seed << "). Paper: hardware prototypes.\n\n"
        << "| source | y [mm] | z [mm] | x [mm] | yaw [rad] |\n|---|---|---|---|---|\n"
        << "| ccma simulation | " << Fixed(1000 * r.rmse[1], 3) << " | " << Fixed(1000 * r.rmse[2], 3) << " | "
        << Fixed(1000 * r.rmse[0], 3) << " | " << Fixed(r.rmse[5], 5) << " |\n";
  for (const auto& row : kPaperFigures) {
    table << "| paper, " << row[0] << " | " << row[1] << " | " << row[2] << " | " << row[3] << " | " << row[4] << " |\n";
  }
  std::ofstream(dir + "/rmse.md") << table.str();
  std::cerr << table.str();

  // Plots in the style of the paper's Figs. 7-12.
  nlohmann::json plots = nlohmann::json::array();
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    std::cerr << "ccma replay: gnuplot not found: plots skipped (apt-get install gnuplot-nox)\n";
  } else {
    std::ostringstream script;
    const char* labels[] = {"x [m]", "y [m]", "z [m]", "roll [rad]", "pitch [rad]", "yaw [rad]"};
    for (const std::string format : {"png", "svg"}) {
      script << (format == "png" ? "set terminal pngcairo size 1000,1100 font 'sans,10'\n"
                                 : "set terminal svg size 1000,1100 font 'sans,10'\n")
             << "set datafile separator ','\nset output '" << dir << "/end_effector." << format << "'\n"
             << "set multiplot layout 4,1 title 'SIMULATION: " << model.name
             << " end-effector, tracked vs commanded (ccma replay)' noenhanced\nset grid\nset key top right\n";
      for (int c : {1, 2, 0, 5}) {  // the paper's order: y, z, x, yaw
        script << "set xlabel 'time [s]'\nset ylabel '" << labels[c] << "'\n"
               << "plot '" << dir << "/end_effector.csv' using 1:" << 2 + c
               << " with lines lw 2 title 'commanded', '' using 1:" << 8 + c << " with lines lw 1 dt 2 title 'tracked'\n";
      }
      script << "unset multiplot\nset output '" << dir << "/bases_xy." << format << "'\n"
             << "set size ratio -1\nset xlabel 'x [m]'\nset ylabel 'y [m]'\n"
             << "set title 'SIMULATION: " << model.name << " bases in the ground plane (ccma replay)' noenhanced\nplot ";
      for (int k = 0; k < model.num_bases(); ++k) {
        script << (k ? ", " : "") << "'" << dir << "/bases.csv' using " << 2 + 6 * k << ":" << 3 + 6 * k
               << " with lines lw 2 title '" << model.mobile_bases[k].name << " set' noenhanced, '' using "
               << 5 + 6 * k << ":" << 6 + 6 * k << " with lines dt 2 title '" << model.mobile_bases[k].name
               << " tracked' noenhanced";
      }
      script << "\nset size noratio\nunset title\nset output\n";
      for (const char* name : {"end_effector", "bases_xy"}) plots.push_back(dir + "/" + name + "." + format);
    }
    std::ofstream(dir + "/replay.gnuplot") << script.str();
    if (std::system(("gnuplot '" + dir + "/replay.gnuplot' 2>/dev/null").c_str()) != 0) {
      std::cerr << "ccma replay: gnuplot failed on " << dir << "/replay.gnuplot\n";
    }
  }

  nlohmann::json out;
  out["model"] = model.name;
  out["simulation"] = true;
  out["converged"] = r.converged;
  out["duration_s"] = r.duration_s;
  out["samples"] = r.samples.size();
  out["noise"] = noise;
  out["controller"] = controller;
  out["rmse"] = {{"x_mm", 1000 * r.rmse[0]},   {"y_mm", 1000 * r.rmse[1]},  {"z_mm", 1000 * r.rmse[2]},
                 {"roll_rad", r.rmse[3]},      {"pitch_rad", r.rmse[4]},    {"yaw_rad", r.rmse[5]}};
  nlohmann::json paper = nlohmann::json::array();
  for (const auto& row : kPaperFigures) {
    paper.push_back({{"experiment", row[0]}, {"y_mm", std::atof(row[1])}, {"z_mm", std::atof(row[2])},
                     {"x_mm", std::atof(row[3])}, {"yaw_rad", std::atof(row[4])}});
  }
  out["paper_hardware_rmse"] = paper;
  out["files"] = {dir + "/end_effector.csv", dir + "/bases.csv", dir + "/rmse.md"};
  out["plots"] = plots;
  if (!r.warning.empty()) out["warning"] = r.warning;
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
