// `ccma import --from=FILE.urdf|FILE.sdf|FILE.xml [--closures=FILE.yaml] [--actuated=J,...] [--keyframe=NAME]
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
#include "documents/import_document.h"
#include "formats/robot_file.h"

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

DEFINE_string(keyframe, "", "import: an MJCF file's keyframe to read the robot at (default: its qpos0) [name]");
DEFINE_bool(strict, false,
            "import: refuse (status 2) an import that joins a closure's frames that are apart in the source or moves "
            "a motor from its source position by more than 1e-6 [flag]");

namespace ccma::cli {
namespace {

std::vector<std::string> SplitNames(const std::string& text, const std::string& flag) {
  std::vector<std::string> names;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (item.empty() || item.size() > kMaxImportNameBytes) throw UsageError("--" + flag + ": empty or overlong name in " + Quote(text));
    names.push_back(item);
  }
  if (!text.empty() && text.back() == ',') throw UsageError("--" + flag + ": trailing comma");
  return names;
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
  if (options->end_effector_link.empty() || options->end_effector_link.size() > kMaxImportNameBytes) {
    throw UsageError("--end_effector: give a link name (LINK[:px,py,pz])");
  }
}

}  // namespace

int RunImport(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "import");
  const std::string from = RequireFlag(FLAGS_from, "from", "import");
  const std::string out_path = RequireFlag(FLAGS_out, "out", "import");
  const RobotFileFormat format = RobotFileFormatOf(from);
  if (format == RobotFileFormat::kUnknown) {
    throw UsageError("ccma import: --from must be a .urdf, .xml (URDF or MuJoCo MJCF), .sdf or .world file");
  }
  if (FLAGS_keyframe.size() > kMaxImportNameBytes) throw UsageError("--keyframe: a name of at most 256 bytes");
  if (format == RobotFileFormat::kSdformat && !FLAGS_closures.empty()) {
    throw UsageError("ccma import: --closures is for URDF (SDFormat holds its loops)");
  }
  ImportOptions options;
  options.actuated = SplitNames(FLAGS_actuated, "actuated");
  options.controlled = SplitNames(FLAGS_controlled, "controlled");
  if (!FLAGS_end_effector.empty()) ParseEndEffector(FLAGS_end_effector, &options);
  options.collision_radius = FLAGS_collision_radius;
  options.strict = FLAGS_strict;
  std::string why;
  if (!options.IsValid(&why)) throw UsageError("--" + why);
  OutputFile out(out_path, "out");  // checked before the work
  // Mesh paths relative to the model file: the two can be moved together.
  options.model_folder = std::filesystem::absolute(out_path).parent_path().string();
  const RobotDescription robot = ReadRobotFile(from, format, FLAGS_closures, options.actuated, FLAGS_keyframe);
  for (const std::string& warning : robot.warnings) std::cerr << "ccma import: warning: " << warning << "\n";
  const ImportedRobot imported = ImportRobot(robot, options);
  documents::Document document = documents::ImportDocument(imported, options);
  PrintWarnings(document, "import");
  if (imported.controlled_chosen) {
    std::string names;
    for (const std::string& name : imported.controlled) names += (names.empty() ? "" : ",") + name;
    std::cerr << "ccma import: controlled components chosen: " << names << " (the controls move "
              << imported.controlled.size() << " end-effector DOF at home; choose others with --controlled)\n";
  }
  out.stream() << imported.yaml;
  out.Commit();
  document.json["out"] = out_path;
  PrintJson(document.json);
  return 0;
}

}  // namespace ccma::cli
