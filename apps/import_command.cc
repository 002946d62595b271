// `ccma import --from=FILE.urdf|FILE.sdf [--closures=FILE.yaml] [--actuated=J,...]
//  --end_effector=LINK[:px,py,pz] [--controlled=x,y,z,...] [--collision_radius=R] --out=MODEL.yaml`:
// a robot described elsewhere -> a model file assembled at home
// (analyses/robot_import.h, docs/import.md).
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <gflags/gflags.h>

#include "analyses/robot_import.h"
#include "ccma/internal/format.h"
#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "formats/sdformat_reader.h"
#include "formats/urdf_reader.h"

DEFINE_string(closures, "", "import: the URDF's closure file (closed_loop, type, name_mot; docs/import.md) [path]");
DEFINE_string(actuated, "", "import: the actuated joints, comma-separated (URDF: overrides name_mot) [names]");
DEFINE_string(end_effector, "",
              "import: the link carrying the end-effector, optionally with the controlled point in that "
              "link's frame: LINK[:px,py,pz] [name[:m,m,m]]");
DEFINE_string(controlled, "",
              "import: the controlled components; default the ones the controls move at home, translations "
              "first [x,y,z,roll,pitch,yaw]");

DEFINE_double(collision_radius, 0,
              "import: give every body capsules of this radius along the segments between its joint points "
              "(0: no collision geometry) [m, 0 or in [1e-4, 10]]");

namespace ccma::cli {
namespace {

std::vector<std::string> SplitNames(const std::string& text, const std::string& flag) {
  std::vector<std::string> names;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (item.empty() || item.size() > 256) throw UsageError("--" + flag + ": empty or overlong name in " + Quote(text));
    names.push_back(item);
  }
  if (!text.empty() && text.back() == ',') throw UsageError("--" + flag + ": trailing comma");
  return names;
}

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

void ParseEndEffector(const std::string& text, ImportOptions* options) {
  const std::size_t colon = text.rfind(':');
  options->end_effector_link = text.substr(0, colon);
  if (colon != std::string::npos) {
    const Eigen::VectorXd p = ParseNumberList(text.substr(colon + 1), "end_effector");
    if (p.size() != 3) throw UsageError("--end_effector: the point needs 3 numbers (LINK:px,py,pz) [m]");
    if (p.cwiseAbs().maxCoeff() > 1e4) throw UsageError("--end_effector: the point must lie within 1e4 m");
    options->end_effector_point_L = p;
  }
  if (options->end_effector_link.empty() || options->end_effector_link.size() > 256) {
    throw UsageError("--end_effector: give a link name (LINK[:px,py,pz])");
  }
}

}  // namespace

int RunImport(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "import");
  const std::string from = RequireFlag(FLAGS_from, "from", "import");
  const std::string out_path = RequireFlag(FLAGS_out, "out", "import");
  const bool sdf = EndsWith(from, ".sdf") || EndsWith(from, ".world");
  if (!sdf && !EndsWith(from, ".urdf") && !EndsWith(from, ".xml")) {
    throw UsageError("ccma import: --from must be a .urdf or .sdf file");
  }
  if (sdf && !FLAGS_closures.empty()) throw UsageError("ccma import: --closures is for URDF (SDFormat holds its loops)");
  ImportOptions options;
  options.actuated = SplitNames(FLAGS_actuated, "actuated");
  options.controlled = SplitNames(FLAGS_controlled, "controlled");
  if (!FLAGS_end_effector.empty()) ParseEndEffector(FLAGS_end_effector, &options);
  if (!(FLAGS_collision_radius == 0 || (FLAGS_collision_radius >= 1e-4 && FLAGS_collision_radius <= 10))) {
    throw UsageError("--collision_radius: must be 0 or in [1e-4, 10] m, got " + FormatG(FLAGS_collision_radius));
  }
  options.collision_radius = FLAGS_collision_radius;
  OutputFile out(out_path, "out");  // checked before the work
  // Mesh paths relative to the model file: the two can be moved together.
  options.model_folder = std::filesystem::absolute(out_path).parent_path().string();
  const RobotDescription robot = sdf ? ReadSdformat(from, options.actuated) : ReadUrdf(from, FLAGS_closures);
  for (const std::string& warning : robot.warnings) std::cerr << "ccma import: warning: " << warning << "\n";
  const ImportedRobot imported = ImportRobot(robot, options);
  for (const std::string& warning : imported.warnings) std::cerr << "ccma import: warning: " << warning << "\n";
  if (imported.controlled_chosen) {
    std::string names;
    for (const std::string& name : imported.controlled) names += (names.empty() ? "" : ",") + name;
    std::cerr << "ccma import: controlled components chosen: " << names << " (the controls move "
              << imported.controlled.size() << " end-effector DOF at home; choose others with --controlled)\n";
  }
  out.stream() << imported.yaml;
  out.Commit();
  nlohmann::json summary = {{"out", out_path},
                            {"bodies", imported.model.num_bodies()},
                            {"joints", static_cast<int>(imported.model.joints.size())},
                            {"closures", imported.closures},
                            {"actuated", imported.actuated},
                            {"controlled", imported.controlled},
                            {"controlled_chosen", imported.controlled_chosen},
                            {"assembled", true},
                            {"residual_energy", imported.residual_energy},
                            {"controls", ToJson(imported.model.home_controls())}};
  if (options.collision_radius > 0) {
    summary["collision_capsules"] = imported.collision_capsules;
    summary["collision_ignored_pairs"] = imported.collision_ignored_pairs;
  }
  PrintJson(summary);
  return 0;
}

}  // namespace ccma::cli
