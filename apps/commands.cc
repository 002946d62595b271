#include "apps/commands.h"

#include <algorithm>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include <ceres/version.h>
#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/flags.h"
#include "ccma/internal/format.h"

namespace ccma::cli {
namespace {

const std::vector<std::string> kControlFlags = {"method", "max_step_m", "max_step_rad", "lambda"};

// --mocap_noise_m/_rad where there is no --noise to override (statics, design).
const std::map<std::string, std::string> kPoseNoiseHelp = {
    {"mocap_noise_m", "the bases' pose noise sigma on x and y, for the end-effector's covariance (default 0.001) [m]"},
    {"mocap_noise_rad", "the bases' pose noise sigma on the heading, for the end-effector's covariance (default 0.003) "
                        "[rad]"}};

std::map<std::string, std::string> WithPoseNoiseHelp(std::map<std::string, std::string> help) {
  help.insert(kPoseNoiseHelp.begin(), kPoseNoiseHelp.end());
  return help;
}

std::vector<std::string> Concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// One function per command (the registry entry), in help order.
Command CheckCommand() {
  return {"check", "validate a model: counts, mobility (which bodies move freely), assembly at home",
          "ccma check --model=FILE",
          "Validates the model and analyses it at home: counts, constraint rows, the numerical mobility\n"
          "(rank of dC/ds with the controls fixed, end-effector DOF when the controls move) and whether\n"
          "the home configuration is assembled. Warns on stderr when the mechanism is not rigid with its\n"
          "controls fixed (naming the bodies each free motion moves) or not assembled at home.\n"
          "Beyond 100 bodies the ranks come from a sparse QR (SuiteSparseQR), in time and memory\n"
          "proportional to the model; above 20,000 bodies the analysis is refused (exit 2).",
          {"model", "obstacles"}, RunCheck};
}

Command SimulateCommand() {
  return {"simulate", "forward problem: assemble the mechanism at given controls",
          "ccma simulate --model=FILE [--controls=u0,u1,...] [--from=RESULT.json] [--loaded]\n"
          "              [--wrench=fx,fy,fz,mx,my,mz] [--max_minutes=10]",
          "Forward problem: assembles the mechanism for the controls, walking them from the start in\n"
          "sub-steps (2 cm / 0.02 rad) so that it stays on the assembly branch it starts on. The start is\n"
          "home, or the configuration and controls in a JSON document printed by `ccma simulate` or\n"
          "`ccma control` (--from; then --controls defaults to that document's controls, so the result is\n"
          "reproduced exactly). Warns on stderr when not assembled, not converged or a branch jump.\n"
          "--loaded (a model with stiffness keys): the mechanism then settles under gravity, the payload and\n"
          "--wrench with its springs yielding and the controls held: bodies, joints and end_effector are the\n"
          "loaded configuration (nonlinear, not linearised), deflection {end_effector [m, rad], max_body_m,\n"
          "held} is its difference from the rigid assembly, and loaded {converged, iterations,\n"
          "unbalanced_load, yields} says how it was found (warns when it was not). Work bounded by its cost:\n"
          "a walk estimated (from its first sub-steps) over 5 s says how long on stderr, then a progress line\n"
          "every 10 s; one estimated over --max_minutes is refused (status 2, naming the estimate).",
          {"model", "controls", "from", "obstacles", "loaded", "wrench", "max_minutes"}, RunSimulate,
          {{"from", "start from the configuration and controls of a JSON document printed by `ccma simulate` or "
                    "`ccma control` instead of home (at most 4 MiB, nested at most 64 levels) [path]"}}};
}

Command ControlCommand() {
  return {"control", "find the controls that bring the end-effector to a target pose",
          "ccma control --model=FILE --target=x,y,z,roll,pitch,yaw [--controls=...] [--method=lm|bfgs]\n"
          "             [--max_step_m=0.01] [--max_step_rad=0.005] [--lambda=0.5]\n"
          "             [--singularity_weight=0] [--singularity_threshold=0.1] [--pivot_weight=0]\n"
          "             [--pivot_threshold=0.001] [--secondary=none|spread|sigma|travel] [--secondary_weight=1]\n"
          "             [--clearance_m=0.5] [--compensate] [--wrench=fx,fy,fz,mx,my,mz] [--max_minutes=10]",
          "Kinematic control: finds controls that put the end-effector at the target, walking there in\n"
          "small end-effector steps from the start controls (home, or --controls). --target takes all six\n"
          "components, or only the model's controlled ones in the order x y z roll pitch yaw. Warns on\n"
          "stderr when the target is not reached, and when the returned controls, simulated from home\n"
          "(`ccma simulate --controls=...`), land on another assembly branch (reproduce the result with\n"
          "`ccma simulate --from=<this JSON>`). Redundant systems (more effective controls than\n"
          "controlled components) can keep the smallest singular value of dX/du (--singularity_weight)\n"
          "and the pivot ratio of dG/ds (--pivot_weight) away from zero, or keep bases apart / travel\n"
          "little (--secondary), in the null space of the end-effector task: the end-effector error is\n"
          "unchanged (docs/cli.md). --compensate (a model with stiffness keys): the controls put the\n"
          "loaded end-effector (ccma simulate --loaded, under gravity, the payload and --wrench) on the target;\n"
          "end_effector, bodies, joints and error are then the loaded ones, and compensation {converged,\n"
          "rounds, miss, aim, rigid_end_effector} tells how (the rigid end-effector is off by about the\n"
          "deflection). Work bounded by its cost: a path estimated (from its first steps) over 5 s says how\n"
          "long on stderr, then a progress line every 10 s; one estimated over --max_minutes is refused\n"
          "(status 2, naming the estimate).",
          Concat(Concat({"model", "target", "controls", "obstacles", "compensate", "wrench", "max_minutes"},
                        SecondaryFlagNames()),
                 kControlFlags),
          RunControl};
}

Command TrajectoryCommand() {
  return {"trajectory", "follow end-effector waypoints; one CSV row per control step",
          "ccma trajectory --model=FILE --waypoints=FILE.csv --out=FILE.csv [--controls=...] [--obstacles=FILE]\n"
          "                [--compensate [--wrench=fx,fy,fz,mx,my,mz]]\n"
          "                [--method=lm|bfgs] [--max_step_m=0.01] [--max_step_rad=0.005] [--lambda=0.5] [--max_minutes=10]\n"
          "                [singularity and secondary flags, as ccma control]",
          "Follows end-effector waypoints (docs/waypoints.md) in small control steps and writes one CSV row\n"
          "per step (header names carry units). Stops at the first waypoint it cannot reach and warns.\n"
          "Prints the conditioning along the path (smallest singular value of dX/du, pivot ratio of\n"
          "dG/ds); the singularity barriers and secondary objectives act at every step as in ccma control.\n"
          "With --compensate (a model with stiffness keys) every step puts the loaded, deflected end-effector\n"
          "on the path: each row is the loaded configuration. Work bounded by its cost: a path estimated\n"
          "(from its first steps) over 5 s says how long on stderr, then a progress line every 10 s; one\n"
          "estimated over --max_minutes is refused (status 2, naming the estimate), nothing written.",
          Concat(Concat({"model", "waypoints", "out", "controls", "obstacles", "compensate", "wrench", "max_minutes"},
                        SecondaryFlagNames()),
                 kControlFlags),
          RunTrajectory, {{"out", "the CSV to write, one row per control step [path]"}}};
}

Command PlanCommand() {
  return {"plan", "optimise a waypoint path's controls together (smooth, short, round obstacles)",
          "ccma plan --model=FILE --waypoints=FILE.csv --out=FILE.csv [--controls=...] [--obstacles=FILE]\n"
          "          [--plan_iterations=200] [--plan_time_s=120] [--path_weight=0.01] [--smoothness_weight=1]\n"
          "          [--travel_weight=0.01] [--max_step_m=0.01] [--max_step_rad=0.005] [--lambda=0.5]",
          "Whole-trajectory planning: walks the waypoints greedily as ccma trajectory does, then optimises\n"
          "the controls of all the steps together: end-effector error at the waypoints (and, weakly, on the\n"
          "straight path between them), smoothness and travel of the bases, with every step's joint limits\n"
          "and clearance >= collision.margin held. Between waypoints the end-effector may leave the straight\n"
          "path, so the plan finds its way round an obstacle where the greedy walk stalls. The plan is then\n"
          "finished: every step below the margin is re-solved back to it, and where the clearance half way\n"
          "between two steps falls more than 1e-6 m below it, that midpoint becomes a step of its own. The\n"
          "plan is kept only if it is no worse than the greedy trajectory (waypoints reached, base travel,\n"
          "clearance); otherwise the greedy one is written, with a warning that names the pair, the step and\n"
          "the shortfall. A line on stderr every 10 s tells a long plan's progress; --plan_time_s bounds the\n"
          "seeds and the optimisation (JSON stopped_by). Same CSV as trajectory. Models with differential\n"
          "bases are refused (exit 2).",
          {"model", "waypoints", "out", "controls", "obstacles", "plan_iterations", "plan_time_s", "path_weight",
           "smoothness_weight", "travel_weight", "max_step_m", "max_step_rad", "lambda"},
          RunPlan, {{"out", "the CSV to write, one row per step, as ccma trajectory's [path]"}}};
}

Command StaticsCommand() {
  return {"statics", "joint reactions and control efforts under gravity, payload and a wrench",
          "ccma statics --model=FILE [--controls=...] [--wrench=fx,fy,fz,mx,my,mz] [--mocap_noise_m=0.001]\n"
          "             [--mocap_noise_rad=0.003] [--obstacles=FILE]",
          "Static equilibrium of the mechanism assembled at the controls (home by default) under gravity on\n"
          "every mass, the end-effector's payload and an external wrench on the end-effector body (world\n"
          "frame, force at the end-effector point): the force and moment every joint's between[0] exerts on\n"
          "its between[1] (world frame, moment about the joint's current point) and the effort every\n"
          "control must supply (N along a base's x or y, N*m about its heading, N*m or N at an actuated\n"
          "joint), analytic from the constraint Jacobians. Statically indeterminate mechanisms get the\n"
          "minimum-norm reactions (determinate: false); effort_limits and push_limit are checked\n"
          "(within_limits, limiting) and payload_capacity {mass [kg], limiting} is the largest payload they\n"
          "allow here. ee_covariance: the end-effector pose's 6x6 covariance from the bases'\n"
          "pose noise (the replay's motion-capture model) through dX/du. With stiffness keys in the model\n"
          "(compliance) the reactions and efforts are the compliant mechanism's (compliant_reactions), and\n"
          "deflection {end_effector [m, rad], max_body_m, held}, ee_compliance (6x6), ee_stiffness (its\n"
          "inverse, or null with ee_stiffness_note) and most_compliant {direction, compliance [m/N]} give\n"
          "how far the loads make it yield with the controls held (linear). Warns when not assembled,\n"
          "unbalanced, indeterminate, beyond a limit or not held by its springs.",
          {"model", "controls", "wrench", "mocap_noise_m", "mocap_noise_rad", "obstacles"}, RunStatics, kPoseNoiseHelp};
}

Command GenerateCommand() {
  return {"generate", "write a generated model (N-base CCMA, Stewart-Gough platform or N quadrupeds)",
          "ccma generate --agents=N [--kind=ccma|stewart_gough|legged] --out=FILE.yaml",
          "Writes a generated model, validated before it is written: a Stewart-like CCMA with N mobile\n"
          "bases (the family of 6dof_six_agents), or with --kind=stewart_gough an N-leg UPS platform on\n"
          "the ground with actuated prismatic legs and no mobile base, or with --kind=legged a 6-DOF\n"
          "platform on N quadrupeds (legged bases; the family of 6dof_three_legged).",
          {"agents", "kind", "out"}, RunGenerate, {{"out", "the model file to write (YAML) [path]"}}};
}

Command ImportCommand() {
  return {"import", "convert a URDF (with closures), SDFormat or MuJoCo MJCF robot into a model file",
          "ccma import --from=FILE.urdf|FILE.sdf|FILE.xml [--closures=FILE.yaml] [--actuated=J,...] [--keyframe=NAME]\n"
          "            --end_effector=LINK[:px,py,pz] [--controlled=x,y,z,roll,pitch,yaw] [--collision_radius=R]\n"
          "            [--strict] --out=MODEL.yaml",
          "Converts a robot described elsewhere into a model file (docs/import.md): every link a body, every\n"
          "joint kept, each loop closure (URDF: the closure file's closed_loop pairs; SDFormat: its own\n"
          "loops) a fixed (6d) or spherical (3d) joint. The written model is assembled at home (the source's\n"
          "zero configuration, solved with the motors held; if the loops cannot close so, with the motors\n"
          "free and a warning) and every revolute and prismatic joint carries q_home, so every q ccma\n"
          "reports is the source's joint position. Without --end_effector, the one `ccma export` stored.\n"
          "Without --controlled (and none stored), the end-effector components the motors move at home,\n"
          "x y z roll pitch yaw in this order, each kept if it raises the rank (said on stderr).\n"
          "With --collision_radius, every body gets capsules of that radius along the segments between its\n"
          "joint points (robot files' collision meshes are not used), so that --obstacles and clearance\n"
          "work; pairs of bodies closer than the margin at home are ignored (they touch by design).\n"
          "SDFormat 1.4 to 1.6 is read with its own version's meaning; a model with no joint to world has its\n"
          "root link welded (said). A Gazebo world gives its one model that is not static and its gravity;\n"
          "its own <include>s are skipped (said). An .xml whose root is <mujoco> is MuJoCo MJCF, compiled by\n"
          "MuJoCo after ccma's checks, read at --keyframe (default qpos0). closure_gaps give how far apart\n"
          "each closure's frames are in the source, motor_moves how far assembling moved each motor; any\n"
          "beyond 1e-6 is named on stderr, and --strict refuses the import then (exit 2).\n"
          "Exit 2 naming the file, the element and the name for a malformed source, an unknown name, a\n"
          "closure that cannot be assembled, or --controlled components the motors cannot move.",
          {"from", "closures", "actuated", "end_effector", "controlled", "collision_radius", "keyframe", "strict", "out"},
          RunImport,
          {{"from", "the robot file: URDF (.urdf, .xml), SDFormat (.sdf, .world) or MJCF (.xml), at most 16 MiB [path]"},
           {"out", "the model file to write (YAML); mesh paths are written relative to its folder [path]"}}};

}

Command BenchCommand() {
  return {"bench", "time forward solves and control steps (LM, BFGS) on models",
          "ccma bench --model=FILE | --all [--models_dir=DIR] | --scaling  [--steps=N] [--seed=1] [--out=DIR]\n"
          "           [--max_minutes=10]",
          "The paper's convergence study: seeded paper-size control steps (10 mm + 0.005 rad) solved by LM\n"
          "and BFGS with implicit-function and finite-difference gradients, the warm forward solve and the\n"
          "Jacobians, all in one run; medians and p95. --out writes per-step CSVs, tables and plots (moved\n"
          "into DIR at the end: a link planted at one of their names is replaced, never followed).\n"
          "Work bounded by its cost: each model's control steps are timed as they are solved; a model\n"
          "estimated over 5 s says how long on stderr, then a progress line every 10 s; one estimated over\n"
          "--max_minutes is refused (status 2, naming the estimate).",
          {"model", "all", "models_dir", "scaling", "steps", "seed", "out", "max_minutes"}, RunBench,
          {{"out", "folder for the per-step CSVs, tables and plots, created if missing (default: no files) [path]"}}};
}

Command ReplayCommand() {
  return {"replay", "simulate the closed loop: bases tracking the plan from motion capture",
          "ccma replay --model=FILE --waypoints=FILE.csv --out=DIR [--noise=default|none] [--seed=1]\n"
          "            [--max_minutes=10] [noise, tracking and control flags]",
          "The paper's closed loop, simulated: the control solution of every path step is fed to the bases,\n"
          "each base tracks it with a PI controller from simulated motion capture, and the chain follows\n"
          "by forward simulation. Writes CSVs, an RMSE table and plots into DIR (SIMULATION, not hardware;\n"
          "moved into DIR at the end: a link planted at one of their names is replaced, never followed).\n"
          "Warns on stderr when the plan did not converge or the chain was torn. Legged bases walk with a\n"
          "trotting gait (--gait_hz, --gait_bob_m, --gait_sway_rad): their bodies bob and sway while they\n"
          "move, and the JSON's \"gait\" separates the end-effector error due to the gait from tracking.\n"
          "Work bounded by its cost: a replay whose chain solves are estimated (from the first ones) over 5 s\n"
          "says how long on stderr, then a progress line every 10 s; one estimated over --max_minutes is\n"
          "refused (status 2, naming the estimate), nothing written.",
          Concat({"model", "waypoints", "out", "noise", "seed", "mocap_noise_m", "mocap_noise_rad", "latency_s",
                  "slip", "kp", "ki", "controller_hz", "max_wheel_speed", "gait_hz", "gait_bob_m", "gait_sway_rad",
                  "obstacles", "max_minutes"},
                 kControlFlags),
          RunReplay, {{"out", "folder for the CSVs, the RMSE table and the plots, created if missing [path]"}}};
}

Command WorkspaceCommand() {
  return {"workspace", "map the reachable end-effector poses and their conditioning",
          "ccma workspace --model=FILE --out=FILE.csv [--x=lo:hi] [--y=lo:hi] [--z=lo:hi] [--roll=lo:hi]\n"
          "               [--pitch=lo:hi] [--yaw=lo:hi] [--resolution=11 | --samples=N --seed=1] [--threads=1]\n"
          "               [--tile_size=0] [--plot=DIR] [--store=DIR] [--obstacles=FILE] [--max_minutes=10]\n"
          "               [--method=lm|bfgs] [--max_step_m=0.01] [--max_step_rad=0.005] [--lambda=0.5]",
          "Workspace map: samples end-effector poses over the given ranges of controlled components (a grid\n"
          "with --resolution points per range, or --samples seeded uniform draws; components not sampled keep\n"
          "their home value) and reaches each by continuation from the nearest already reached sample (or\n"
          "home) in small control steps (a sample more than 100000 steps away is unreachable, not walked).\n"
          "Writes one CSV row per sample: the controlled components, reachable (1/0), residual_energy [m^2],\n"
          "sigma_min (smallest singular value of dX/du, 0 when unreachable), error [m or rad], rcond (pivot\n"
          "ratio of dG/ds), joint limits, u0, u1, ... (empty when unreachable).\n"
          "The map is computed in tiles of --tile_size cells per range (each continued from the tiles nearer\n"
          "home); results do not depend on --threads. --plot writes reachability and sigma_min maps over the\n"
          "first two ranges. --store=DIR keeps every finished tile there as it completes: the same command\n"
          "run again (after Ctrl-C, say) reads them back and computes only the rest; the map is the same.\n"
          "A tile file that is not one ccma wrote (a link, FIFO or folder, too large, a bad value) is computed\n"
          "again; a store.json that is not this map's manifest is refused (status 2).\n"
          "Prints {samples, reachable, tiles, seconds, ...}; a percentage bar on stderr at a terminal.\n"
          "The run is timed on its first samples (and the CSV's computed columns once at home): a run estimated\n"
          "over 5 s says how long on stderr, then a progress line every 10 s; one estimated over --max_minutes\n"
          "is refused (status 2, naming the estimate and the --max_minutes that would allow it).",
          Concat({"model", "out", "x", "y", "z", "roll", "pitch", "yaw", "resolution", "samples", "seed", "threads",
                  "tile_size", "plot", "obstacles", "store", "max_minutes"},
                 kControlFlags),
          RunWorkspace, {{"out", "the CSV to write, one row per sample [path]"}}};
}

Command DesignCommand() {
  return {"design", "move joint points or link lengths until every target pose is reachable",
          "ccma design --model=FILE --targets=FILE.csv --out=NEW.yaml [--vary=JOINT.x|.y|.z|.point,...]\n"
          "            [--vary_length=ANCHOR:JOINT,...] [--max_change=0.5] [--min_length=0.02]\n"
          "            [--min_singular_value=0.02] [--target_tolerance=1e-6] [--design_iterations=30]\n"
          "            [--objective=reach|payload|peak_push|ee_std|stiffness|deflection] [--mocap_noise_m=0.001]\n"
          "            [--mocap_noise_rad=0.003] [--max_minutes=10]\n"
          "            [--method=lm|bfgs] [--max_step_m=0.01] [--max_step_rad=0.005] [--lambda=0.5]",
          "Adjusts the named geometry (joint points in world home coordinates [m], link lengths [m]) so that\n"
          "every target pose of the waypoint CSV (docs/waypoints.md; times ignored) is reachable with margin:\n"
          "control error below --target_tolerance, assembled, joint limits held, smallest singular value of\n"
          "dX/du at least --min_singular_value (docs/design.md). Writes the model file with only the named\n"
          "joints' point numbers changed (comments and layout kept) and prints {converged, reached (one\n"
          "boolean per target, in the written model), reached_before, changed (parameter, old, new [m]),\n"
          "changed_points, targets, iterations}; a warning on stderr when not converged. With --objective,\n"
          "once every target is reached with margin the design keeps moving to raise the payload the model\n"
          "can hold within its effort_limits and push_limit, or to lower the largest base push, the\n"
          "end-effector's standard deviation, or (a compliant model: stiffness keys) the largest eigenvalue\n"
          "of the translational block of ee_compliance [m/N] (stiffness) or the end-effector's deflection\n"
          "under gravity and the payload [m] (deflection), at the worst target; JSON objective {name, unit,\n"
          "before, after, iterations, stopped} (docs/statics.md). The iterations are timed as they go (the\n"
          "objective's on their own): a design estimated over 5 s says how long on stderr, then a progress\n"
          "line every 10 s; one estimated over --max_minutes is refused (status 2, naming the estimate and the\n"
          "--max_minutes that would allow it), nothing written.",
          Concat({"model", "targets", "out", "vary", "vary_length", "max_change", "min_length", "min_singular_value",
                  "target_tolerance", "design_iterations", "objective", "mocap_noise_m", "mocap_noise_rad",
                  "max_minutes"},
                 kControlFlags),
          RunDesign, WithPoseNoiseHelp({{"out", "the model file to write: the input with the varied points changed [path]"}})};
}

Command ExportCommand() {
  return {"export", "write a model as URDF (+ closure file), SDFormat or MuJoCo MJCF, loops included",
          "ccma export --model=FILE --format=urdf|sdf|mjcf --out=FILE",
          "Writes the model as URDF (a spanning tree; loop joints, motors, end-effector in OUT.closures.yaml),\n"
          "SDFormat 1.7 with its loops (links at home), or MuJoCo MJCF at the assembled home (qpos0), cut joints\n"
          "as connect or weld equalities, a position actuator per control; `ccma import` gives each back. Prints\n"
          "{out, format, closures, links, joints, loops} (mjcf: bodies, joints, equalities, actuators, loops).",
          {"model", "format", "out"}, RunExport,
          {{"out", "the URDF or SDFormat file to write (URDF: also its closure file OUT.closures.yaml) [path]"}}};
}

}  // namespace

const std::vector<Command>& Commands() {
  static const std::vector<Command> commands = {
      CheckCommand(),
      SimulateCommand(),
      ControlCommand(),
      TrajectoryCommand(),
      PlanCommand(),
      StaticsCommand(),
      DynamicsCommand(),  RetimeCommand(),
      GenerateCommand(),
      ImportCommand(),
      ExportCommand(),
      BenchCommand(),
      ReplayCommand(),
      ViewCommand(),
      WorkspaceCommand(),
      DesignCommand()};
  return commands;
}

const Command& CommandNamed(const std::string& name) {
  for (const Command& command : Commands()) {
    if (command.name == name) return command;
  }
  throw std::logic_error("no command '" + name + "'");
}

void ParseCommandFlags(const std::vector<std::string>& args, const std::string& command) {
  const Command& entry = CommandNamed(command);
  ParseFlags(args, std::set<std::string>(entry.flags.begin(), entry.flags.end()), command);
}

std::string CommandHelp(const Command& command) {
  std::ostringstream os;
  std::string synopsis = command.synopsis;  // continuation lines aligned under the first's "ccma"
  for (size_t p = synopsis.find('\n'); p != std::string::npos; p = synopsis.find('\n', p + 1)) synopsis.insert(p + 1, 7, ' ');
  os << "usage: " << synopsis << "\n\n" << command.description << "\n\nflags:\n";
  for (const std::string& name : command.flags) {
    gflags::CommandLineFlagInfo info;
    if (!gflags::GetCommandLineFlagInfo(name.c_str(), &info)) continue;
    const std::string value = info.type == "bool" ? "" : "=" + std::string(info.type == "string" ? "TEXT" : info.type == "double" ? "NUMBER" : "INTEGER");
    const auto own = command.flag_help.find(name);
    os << "  --" << name << value << "\n      " << (own != command.flag_help.end() ? own->second : info.description);
    // -1: "not given" (the description says what applies then).
    if (!info.default_value.empty() && info.default_value != "0" && info.default_value != "false" &&
        info.default_value != "-1") {
      os << " (default: " << (info.type == "double" ? FormatG(std::stod(info.default_value)) : info.default_value)
         << ")";
    }
    os << "\n";
  }
  os << "\nResults: one JSON document on stdout; diagnostics and warnings on stderr.\n"
        "Exit status: 0 ran (the JSON may still say it failed), 1 failure, 2 bad usage or bad input\n"
        "(a message on stderr, nothing on stdout). Reference: docs/cli.md.\n";
  return os.str();
}

std::string GlobalHelp() {
  std::ostringstream os;
  size_t width = 0;  // names padded to one column
  for (const Command& command : Commands()) width = std::max(width, command.name.size());
  os << "ccma: simulation and kinematic control of Constrained Collaborative Mobile Agents\n\n"
        "usage: ccma COMMAND --NAME=VALUE ...\n\ncommands:\n";
  for (const Command& command : Commands()) {
    os << "  ccma " << command.name << std::string(width + 2 - command.name.size(), ' ') << command.summary << "\n";
  }
  os << "\n`ccma COMMAND --help` describes a command and its flags (with units and defaults);\n"
        "`ccma --version` prints the version. Results are one JSON document on stdout; diagnostics\n"
        "go to stderr. Exit status: 0 ok, 1 failure, 2 bad usage or bad input. Reference: docs/cli.md.\n";
  return os.str();
}

std::string VersionLine() {
  return std::string("ccma ") + CCMA_VERSION + " (" + CCMA_BUILD_TYPE + "; Ceres " + CERES_VERSION_STRING +
         ", Eigen " + std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
         std::to_string(EIGEN_MINOR_VERSION) + ")";
}

Model LoadModelOrThrow(const std::string& path) {
  std::vector<std::string> warnings;
  Model model = LoadModel(path, &warnings);
  if (!FLAGS_obstacles.empty()) AddObstaclesFromFile(FLAGS_obstacles, &model, &warnings);
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  return model;
}

std::vector<Waypoint> WaypointsFlag(const std::string& command) {
  try {
    return LoadWaypoints(RequireFlag(FLAGS_waypoints, "waypoints", command));
  } catch (const WaypointError& e) {
    throw UsageError("ccma " + command + ": " + e.what());
  }
}

ExternalWrench WrenchFlag() {
  ExternalWrench w;
  if (FLAGS_wrench.empty()) return w;
  const Eigen::VectorXd v = ParseNumberList(FLAGS_wrench, "wrench");
  if (v.size() != 6) {
    throw UsageError("--wrench: 6 numbers fx,fy,fz,mx,my,mz (N, N*m) are needed, got " + std::to_string(v.size()));
  }
  for (int i = 0; i < 6; ++i) {
    if (!(std::abs(v[i]) <= 1e6)) throw UsageError("--wrench: entry " + std::to_string(i) + " must lie in [-1e6, 1e6]");
  }
  w.force = v.head<3>();
  w.moment = v.tail<3>();
  return w;
}

Eigen::VectorXd ControlsFlagOrHome(const Model& model) {
  if (FLAGS_controls.empty()) return model.home_controls();
  const Eigen::VectorXd u = ParseNumberList(FLAGS_controls, "controls");
  if (u.size() != model.num_controls()) {
    throw UsageError("--controls: model '" + model.name + "' has " + std::to_string(model.num_bases()) +
                     " mobile bases and " + std::to_string(model.num_actuated_joints()) + " actuated joints, so " +
                     std::to_string(model.num_controls()) + " controls; got " + std::to_string(u.size()));
  }
  for (int i = 0; i < u.size(); ++i) {
    if (std::abs(u[i]) > kMaxMagnitude) {
      throw UsageError("--controls: entry " + std::to_string(i) + " (" + FormatG(u[i]) + ") must lie in [-" +
                       FormatG(kMaxMagnitude) + ", " + FormatG(kMaxMagnitude) + "] (m or rad)");
    }
  }
  return u;
}

ControlOptions ControlOptionsFromFlags() {
  ControlOptions options;
  if (FLAGS_method == "lm") {
    options.method = ControlMethod::kLevenbergMarquardt;
  } else if (FLAGS_method == "bfgs") {
    options.method = ControlMethod::kBfgs;
  } else {
    throw UsageError("--method: " + Quote(FLAGS_method) + " is not lm or bfgs");
  }
  options.max_step_m = FLAGS_max_step_m;
  options.max_step_rad = FLAGS_max_step_rad;
  options.lambda = FLAGS_lambda;
  std::string why;
  if (!options.IsValid(&why)) throw UsageError("control options: --" + why);
  return options;
}

}  // namespace ccma::cli
