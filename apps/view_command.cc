// `ccma view --model=FILE [--trajectory=FILE.csv | --replay=DIR | --workspace=MAP.csv] [--meshes]
// --out=FILE.html`: one self-contained HTML page showing the mechanism in 3D
// (viewer/), animated along a trajectory CSV or a replay directory, or at home
// under the point cloud of a workspace map; with --meshes, the bodies' STL
// meshes embedded and drawn (only from the model file's folder and the
// --mesh_root folders); with collision geometry or --obstacles, the
// shapes drawn and frames closer than the margin marked; with
// --color_by=load, the links coloured by their joints' largest reaction force
// in each frame's statics; with --controls, the model assembled at those
// controls; with --deflection=SCALE (a compliant model, a static view), its
// loaded shape exaggerated SCALE times over the rigid one, coloured by each
// body's deflection; with --dynamics=EFFORTS.csv (`ccma dynamics --out` of
// the trajectory), the bodies the limited actuators drive coloured by effort
// as a share of the limit. Prints {"out", "bytes", "frames", ...} on stdout.
#include <new>
#include <optional>
#include <stdexcept>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "documents/view_document.h"
#include "viewer/frame_efforts.h"
#include "viewer/html.h"
#include "viewer/mesh_files.h"
#include "viewer/scene.h"
#include "viewer/view_frames.h"
#include "viewer/workspace_cloud.h"

DEFINE_string(trajectory, "", "a CSV written by `ccma trajectory` to animate [file]");
DEFINE_string(replay, "", "a directory written by `ccma replay` to animate [directory]");
DEFINE_string(workspace, "",
              "a CSV written by `ccma workspace` to draw as a point cloud over the model at home, coloured by "
              "sigma_min [file]");
DEFINE_bool(meshes, false,
            "draw the bodies' meshes (`meshes:` in the model; STL, at most 16 MiB per file and 64 MiB in all) "
            "[flag]");
DEFINE_string(mesh_root, "",
              "with --meshes: folders, comma-separated, that meshes may come from besides the model file's own "
              "folder (by default a mesh outside that folder, symlinks resolved, is refused with status 2) "
              "[folders]");
DEFINE_string(color_by, "body",
              "what the links are coloured by: body (their kind) or load (the largest reaction force of the joints "
              "that touch each link in every frame's statics, gravity on the masses and payload) [body|load]");

DEFINE_string(dynamics, "",
              "with --trajectory: the `ccma dynamics --out` CSV of that trajectory; each actuator with a limit "
              "colours the body it drives by its effort as a share of the limit [file]");
DEFINE_string(deflection, "",
              "draw the loaded shape of a compliant model (stiffness keys; its loaded equilibrium, as ccma simulate "
              "computes it, under gravity, the payload and --wrench) over the rigid one, its displacement multiplied "
              "by SCALE, each body coloured by its deflection; a static view only (at home or --controls) "
              "[SCALE in (0, 1e6]]");

namespace ccma::cli {

Command ViewCommand() {
  return {"view", "write a self-contained 3D HTML view (animated for a trajectory or replay)",
          "ccma view --model=FILE [--trajectory=FILE.csv | --replay=DIR | --workspace=MAP.csv | --controls=...]\n"
          "          [--dynamics=EFFORTS.csv] [--meshes [--mesh_root=DIR,...]] [--obstacles=FILE.yaml]\n"
          "          [--color_by=body|load]\n"
          "          [--deflection=SCALE [--wrench=fx,fy,fz,mx,my,mz]] --out=FILE.html",
          "Writes one self-contained HTML page (three.js inlined; it fetches nothing) that shows the\n"
          "mechanism in 3D: links as capsules between joint points, bases as discs with a heading arrow,\n"
          "joint markers by type, the end-effector's frame, the ground grid, orbit controls. With a\n"
          "trajectory CSV (`ccma trajectory`) or a replay directory (`ccma replay`) it is animated (play,\n"
          "pause, time slider) with the end-effector's commanded and tracked paths and the bases' paths.\n"
          "Each frame is re-assembled from its controls; frames that are flagged, not assembled or reached\n"
          "by a branch jump are marked red (and counted on stderr and in the JSON). Work bound: a frame more\n"
          "than 1000 assembly sub-steps (20 m or rad of control change) from the last frame assembled, or\n"
          "past 200000 sub-steps in all, is not attempted (flagged, drawn as the last frame assembled;\n"
          "JSON beyond_work_bound_frames). With a workspace map (`ccma workspace`, alone) the model at home\n"
          "under the map's end-effector positions as a point cloud: reachable points coloured by sigma_min\n"
          "[m or rad per control unit], the others grey. With --meshes, the bodies' meshes (`meshes:` in\n"
          "the model: binary or ASCII STL, paths absolute or relative to the model file's folder) are read,\n"
          "embedded and drawn at their pose on each body instead of its capsules; at most 16 MiB per file and\n"
          "64 MiB for all distinct files. Meshes are read only from inside the model file's folder (symlinks\n"
          "resolved) and the folders given with --mesh_root; the page names them relative to the model's\n"
          "folder (or by file name), never by an absolute path. A mesh file outside, missing, unreadable,\n"
          "too large or not a valid STL: exit 2, naming the model file and line, the body and the mesh file\n"
          "(JSON mesh_files, mesh_bytes).\n"
          "With collision geometry (`collision:`, `obstacles:` or --obstacles) the obstacles, bases' cylinders\n"
          "and link capsules are drawn see-through with each frame's clearance and pair; a frame below\n"
          "collision.margin reads \"below margin\", its pair turns red and it is flagged (JSON\n"
          "clearance_below_margin_frames). With --color_by=load each frame's statics is solved (gravity on\n"
          "the masses and payload, no wrench) and each link is coloured by its load, the largest reaction\n"
          "force of the joints that touch it [N], on a scale from 0 to the page's largest (JSON max_load,\n"
          "unbalanced_frames, indeterminate_frames); statics beyond its bounds: exit 2.\n"
          "With --dynamics (and --trajectory: `ccma dynamics --out` of that trajectory) each actuator with a\n"
          "limit colours the body it drives by its effort as a share of the limit (effort_limits; a base's\n"
          "push_limit on the length of its (x, y) effort): 0 to 1 on the load map, beyond 1 magenta, the bar\n"
          "naming the frame's largest share (JSON effort_frames_beyond_limit, max_effort_share). A model\n"
          "without limits, or a CSV without a row at some frame's time: exit 2.\n"
          "With --controls (alone, no trajectory, replay or map) the model is shown assembled at those controls.\n"
          "With --deflection=SCALE (a compliant model: stiffness keys; a static view, at home or --controls)\n"
          "the loaded shape, the loaded equilibrium of `ccma simulate --loaded` under gravity, the payload and\n"
          "--wrench, is drawn over the rigid one with every body's displacement multiplied by SCALE (in\n"
          "(0, 1e6]), each body coloured by its deflection (the largest displacement of its joint points) from\n"
          "0 to the largest, with the scale and the largest deflection in the page (JSON deflection_scale,\n"
          "max_deflection_m, deflection_converged, load_fraction). A rigid model, a bad SCALE or controls that\n"
          "do not assemble: exit 2.",
          {"model", "trajectory", "dynamics", "replay", "workspace", "controls", "meshes", "mesh_root", "color_by",
           "deflection", "wrench", "out", "obstacles"},
          RunView,
          {{"out", "the HTML page to write [path]"},
           {"dynamics", "with --trajectory: its `ccma dynamics --out` CSV, to colour the actuators by effort [file]"}}};
}

namespace {

// --mesh_root: the folders, comma-separated (an empty item is an error).
std::vector<std::string> MeshRoots() {
  std::vector<std::string> roots;
  if (FLAGS_mesh_root.empty()) return roots;
  std::size_t from = 0;
  for (std::size_t comma; (comma = FLAGS_mesh_root.find(',', from)) != std::string::npos; from = comma + 1) {
    roots.push_back(FLAGS_mesh_root.substr(from, comma - from));
  }
  roots.push_back(FLAGS_mesh_root.substr(from));
  for (const std::string& root : roots) {
    if (root.empty()) throw UsageError("ccma view: --mesh_root: an empty folder in '" + FLAGS_mesh_root + "'");
  }
  return roots;
}

// --deflection=SCALE: one finite number in (0, kMaxDeflectionScale].
double DeflectionScaleFlag() {
  const Eigen::VectorXd v = ParseNumberList(FLAGS_deflection, "deflection");
  if (v.size() != 1 || !(v[0] > 0 && v[0] <= viewer::kMaxDeflectionScale)) {
    throw UsageError("ccma view: --deflection: SCALE must be one number in (0, 1e6], not " + Quote(FLAGS_deflection));
  }
  return v[0];
}

// The flags of a static view (--controls, --deflection, --wrench): which
// others they go with, and the deflection request (empty without
// --deflection). A model without stiffness has nothing to deflect.
std::optional<viewer::DeflectionRequest> StaticViewFlags(const Model& model) {
  const bool animated = !FLAGS_trajectory.empty() || !FLAGS_replay.empty() || !FLAGS_workspace.empty();
  if (!FLAGS_controls.empty() && animated) {
    throw UsageError("ccma view: --controls is for a static view, without --trajectory, --replay or --workspace");
  }
  if (!FLAGS_wrench.empty() && FLAGS_deflection.empty()) {
    throw UsageError("ccma view: --wrench goes with --deflection (the loads of the loaded shape)");
  }
  if (FLAGS_deflection.empty()) return std::nullopt;
  if (animated) throw UsageError("ccma view: --deflection is for a static view, without --trajectory, --replay or --workspace");
  if (FLAGS_color_by != "body") throw UsageError("ccma view: --deflection colours the bodies itself: not with --color_by=load");
  viewer::DeflectionRequest request;
  request.scale = DeflectionScaleFlag();
  if (!model.compliant()) {
    throw UsageError("ccma view: --deflection: model " + Quote(model.name) +
                     " has no stiffness keys: it is rigid and nothing deflects (model_format.md, \"Compliance\")");
  }
  request.wrench = WrenchFlag();
  return request;
}

// --color_by: body (the default) or load.
viewer::ColorBy ColorByFlag() {
  if (FLAGS_color_by == "body") return viewer::ColorBy::kBody;
  if (FLAGS_color_by == "load") return viewer::ColorBy::kLoad;
  throw UsageError("ccma view: --color_by must be body or load, not " + Quote(FLAGS_color_by));
}

// The frames to draw: a trajectory's, a replay's, or the one at --controls
// (none: the model at home); *source names them when there are any.
std::vector<viewer::ViewFrame> ViewFramesFromFlags(const Model& model, std::string* source) {
  if (!FLAGS_trajectory.empty()) {
    *source = "trajectory";
    return viewer::FramesFromTrajectory(model, FLAGS_trajectory);
  }
  if (!FLAGS_replay.empty()) {
    *source = "replay";
    return viewer::FramesFromReplay(model, FLAGS_replay);
  }
  if (FLAGS_controls.empty()) return {};
  *source = "controls";
  return {{0.0, ControlsFlagOrHome(model), std::nullopt, std::nullopt, false}};
}

// The file a page is drawn from: the one a message about memory names.
std::string InputPath(const std::string& model_path) {
  for (const std::string* flag : {&FLAGS_workspace, &FLAGS_trajectory, &FLAGS_replay}) {
    if (!flag->empty()) return *flag;
  }
  return model_path;
}

int WriteView(const std::string& model_path);

}  // namespace

int RunView(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "view");
  const std::string model_path = RequireFlag(FLAGS_model, "model", "view");
  // Within the bounds a page takes well under 1 GB (docs/security.md); a
  // machine with less to give ends here, naming the file, not in bad_alloc.
  try {
    return WriteView(model_path);
  } catch (const std::bad_alloc&) {
    throw UsageError("ccma view: " + InputPath(model_path) +
                     ": not enough memory to read it and write the page (docs/security.md, \"Bounds\")");
  }
}

namespace {

// Which of --trajectory, --replay, --workspace and --dynamics go together.
void CheckSourceFlags() {
  if (!FLAGS_trajectory.empty() && !FLAGS_replay.empty()) {
    throw UsageError("ccma view: give --trajectory or --replay, not both");
  }
  // A workspace map is drawn over the model at home: one picture, no animation.
  if (!FLAGS_workspace.empty() && (!FLAGS_trajectory.empty() || !FLAGS_replay.empty())) {
    throw UsageError("ccma view: --workspace goes alone, without --trajectory or --replay");
  }
  if (!FLAGS_dynamics.empty() && FLAGS_trajectory.empty()) {
    throw UsageError("ccma view: --dynamics goes with --trajectory (the trajectory its efforts are of)");
  }
  if (!FLAGS_dynamics.empty() && FLAGS_color_by != "body") {
    throw UsageError("ccma view: --dynamics colours the bodies by effort: not with --color_by=load");
  }
}

int WriteView(const std::string& model_path) {
  const std::string out_path = RequireFlag(FLAGS_out, "out", "view");
  CheckSourceFlags();
  const viewer::ColorBy color_by = ColorByFlag();
  const std::vector<std::string> mesh_roots = MeshRoots();
  if (!mesh_roots.empty() && !FLAGS_meshes) throw UsageError("ccma view: --mesh_root goes with --meshes");
  const Model model = LoadModelOrThrow(model_path);
  const std::optional<viewer::DeflectionRequest> deflection = StaticViewFlags(model);
  std::vector<viewer::ViewFrame> frames;
  std::optional<viewer::WorkspaceCloud> workspace;
  std::optional<viewer::MeshFiles> meshes;
  std::optional<viewer::FrameEfforts> efforts;
  std::string source = "model";
  try {
    if (FLAGS_meshes) meshes = viewer::ReadMeshFiles(model, mesh_roots);
    if (!FLAGS_workspace.empty()) {
      workspace = viewer::CloudFromWorkspaceCsv(model, FLAGS_workspace);
      source = "workspace";
    }
    frames = ViewFramesFromFlags(model, &source);
    if (!FLAGS_dynamics.empty()) efforts = viewer::ReadFrameEfforts(model, FLAGS_dynamics, frames);
  } catch (const viewer::ViewInputError& e) {
    throw UsageError(std::string("ccma view: ") + e.what());
  } catch (const std::invalid_argument& e) {  // no limits to colour by
    throw UsageError(std::string("ccma view: --dynamics: ") + e.what());
  }
  if (!viewer::HasBundle()) {
    throw std::runtime_error("ccma view: this ccma was built without the viewer's JavaScript (three.js and "
                             "esbuild could not be fetched from the npm registry when it was configured; "
                             "configure again with access to the registry and rebuild)");
  }
  viewer::SceneSummary summary;
  std::string scene;
  try {
    scene = viewer::BuildScene(model, frames, source, &summary, workspace ? &*workspace : nullptr,
                               meshes ? &*meshes : nullptr, color_by, deflection ? &*deflection : nullptr,
                               efforts ? &*efforts : nullptr);
  } catch (const std::invalid_argument& e) {  // the statics of --color_by=load beyond their bounds
    throw UsageError(std::string("ccma view: --color_by=load: ") + e.what());
  } catch (const viewer::DeflectionError& e) {
    throw UsageError(std::string("ccma view: --deflection: ") + e.what());
  }
  const std::string html = viewer::ViewerHtml(scene, model.name);
  OutputFile out(out_path, "out");
  out.stream() << html;
  out.Commit();
  documents::Document document =
      documents::ViewDocument(model, summary, html.size(), source, meshes ? &*meshes : nullptr, workspace.has_value(),
                              color_by == viewer::ColorBy::kLoad);
  document.json["out"] = out_path;
  PrintDocument(document, "view");
  return 0;
}

}  // namespace

}  // namespace ccma::cli
