#include "documents/view_document.h"

#include <sstream>
#include <vector>

namespace ccma::documents {
namespace {

// The frames not assembled, reached by a branch jump, beyond the work bound
// or below the clearance margin (all marked red in the page).
void FrameWarnings(const viewer::SceneSummary& summary, const std::string& source, double margin,
                   std::vector<std::string>* warnings) {
  if (summary.not_assembled > 0 || summary.branch_jumps > 0) {
    std::ostringstream text;
    text << summary.not_assembled << " frame(s) not assembled and " << summary.branch_jumps
         << " branch jump(s) while re-assembling the " << source << " (marked red in the page)";
    warnings->push_back(text.str());
  }
  if (summary.beyond_work_bound > 0) {
    std::ostringstream text;
    text << summary.beyond_work_bound << " of them not attempted: more than " << viewer::kMaxViewFrameSubsteps
         << " assembly sub-steps from the last frame assembled, or past " << viewer::kMaxViewSubsteps << " in all";
    warnings->push_back(text.str());
  }
  if (summary.clearance_below_margin > 0) {
    std::ostringstream text;
    text << summary.clearance_below_margin << " frame(s) with a clearance below the margin of " << margin
         << " m (marked red in the page)";
    warnings->push_back(text.str());
  }
}

// Frames whose statics is not balanced or not determinate (colour by load),
// and a loaded shape that is not an equilibrium.
void LoadWarnings(const viewer::SceneSummary& summary, bool loads, std::vector<std::string>* warnings) {
  if (loads && summary.unbalanced_frames > 0) {
    warnings->push_back(std::to_string(summary.unbalanced_frames) +
                        " frame(s) whose joints cannot hold the loads (unbalanced): their loads are a least-squares fit");
  }
  if (loads && summary.indeterminate_frames > 0) {
    warnings->push_back(std::to_string(summary.indeterminate_frames) +
                        " frame(s) statically indeterminate: coloured by the minimum-norm loads");
  }
  if (summary.deflected && !summary.deflected->equilibrium.converged) {
    std::ostringstream text;
    text << "the loaded equilibrium was not found (" << summary.deflected->equilibrium.message
         << "); the shape drawn holds " << summary.deflected->equilibrium.load_fraction << " of the loads";
    warnings->push_back(text.str());
  }
}

}  // namespace

Document ViewDocument(const Model& model, const viewer::SceneSummary& summary, std::size_t bytes,
                      const std::string& source, const viewer::MeshFiles* meshes, bool workspace, bool loads) {
  Document doc;
  nlohmann::json& out = doc.json;
  out = {{"bytes", bytes},
         {"frames", summary.frames},
         {"source", source},
         {"flagged_frames", summary.flagged_frames},
         {"not_assembled_frames", summary.not_assembled},
         {"branch_jumps", summary.branch_jumps}};
  if (summary.beyond_work_bound > 0) out["beyond_work_bound_frames"] = summary.beyond_work_bound;
  if (model.collision.enabled) out["clearance_below_margin_frames"] = summary.clearance_below_margin;
  if (meshes != nullptr) {
    out["mesh_files"] = meshes->files.size();
    out["mesh_bytes"] = meshes->bytes_read;
  }
  if (loads) {
    out["max_load"] = summary.max_load;
    out["unbalanced_frames"] = summary.unbalanced_frames;
    out["indeterminate_frames"] = summary.indeterminate_frames;
  }
  if (summary.deflected) {
    const LoadedEquilibrium& e = summary.deflected->equilibrium;
    out["deflection_scale"] = summary.deflected->scale;
    out["max_deflection_m"] = summary.deflected->max_deflection_m;
    out["deflection_converged"] = e.converged;
    out["load_fraction"] = e.load_fraction;
  }
  if (summary.max_effort_share) {
    out["max_effort_share"] = *summary.max_effort_share;
    out["effort_frames_beyond_limit"] = summary.effort_frames_beyond_limit;
    if (summary.effort_frames_beyond_limit > 0) {
      doc.warnings.push_back(std::to_string(summary.effort_frames_beyond_limit) +
                             " frame(s) with an actuator beyond its effort or push limit (magenta)");
    }
  }
  if (workspace) {
    out["workspace_points"] = summary.workspace_points;
    out["workspace_reachable"] = summary.workspace_reachable;
  }
  FrameWarnings(summary, source, model.collision.margin, &doc.warnings);
  LoadWarnings(summary, loads, &doc.warnings);
  return doc;
}

}  // namespace ccma::documents
