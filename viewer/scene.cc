#include "viewer/scene.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>

#include "ccma/rotation.h"
#include "problems/forward_problem.h"
#include "execution/replay.h"
#include "viewer/stl.h"

namespace ccma::viewer {
namespace {

using nlohmann::json;

// Display precision: 1e-7 m / 1e-7 rad-like. Rounding also keeps the JSON
// short (nlohmann prints the shortest text that reads back the same double).
double Round(double v) { return std::round(v * 1e7) / 1e7; }

json Vec(const Eigen::Vector3d& v) { return json::array({Round(v.x()), Round(v.y()), Round(v.z())}); }

// The points drawn on body b, in b's frame: its joint points and, on the
// end-effector's body, the end-effector point (near-duplicates merged).
std::vector<Eigen::Vector3d> BodyPoints(const Model& model, int b) {
  std::vector<Eigen::Vector3d> points;
  auto add = [&points](const Eigen::Vector3d& p) {
    for (const Eigen::Vector3d& q : points) {
      if ((p - q).norm() < 1e-9) return;
    }
    points.push_back(p);
  };
  if (model.bodies[b].is_mobile_base()) add(Eigen::Vector3d::Zero());  // the base's centre
  for (const Joint& j : model.joints) {
    if (j.body_a == b) add(j.p_A);
    if (j.body_b == b) add(j.p_B);
  }
  if (model.end_effector.body == b) add(model.end_effector.p_B);
  return points;
}

// Capsules between the points: a base's centre to each of its joints; two
// points joined; three or more joined in a ring, ordered by angle around
// their centroid in their best-fit plane (a platform's outline).
json BodyLinks(const std::vector<Eigen::Vector3d>& points, bool is_base) {
  json links = json::array();
  const int n = static_cast<int>(points.size());
  if (is_base) {
    for (int i = 1; i < n; ++i) links.push_back({0, i});
    return links;
  }
  if (n == 2) links.push_back({0, 1});
  if (n < 3) return links;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p / n;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);  // ascending eigenvalues
  const Eigen::Vector3d e1 = eig.eigenvectors().col(2), e2 = eig.eigenvectors().col(1);
  std::vector<std::pair<double, int>> order;
  for (int i = 0; i < n; ++i) order.emplace_back(std::atan2((points[i] - centroid).dot(e2), (points[i] - centroid).dot(e1)), i);
  std::sort(order.begin(), order.end());
  for (int i = 0; i < n; ++i) links.push_back({order[i].second, order[(i + 1) % n].second});
  return links;
}

// Radius [m] of the mechanism at home around its centroid (marker sizes),
// with the lowest and highest corners of the workspace cloud's box when there
// is one: a cloud far larger than the mechanism is seen from farther, so the
// markers grow with it and stay visible.
double Scale(const Model& model, const WorkspaceCloud* workspace) {
  std::vector<Eigen::Vector3d> points;
  for (const Body& b : model.bodies) points.push_back(b.p_WB_home);
  points.push_back(model.end_effector.p_W_home);
  if (workspace != nullptr && !workspace->points.empty()) {
    Eigen::Vector3d lo = workspace->points.front(), hi = lo;
    for (const Eigen::Vector3d& p : workspace->points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    points.push_back(lo);
    points.push_back(hi);
  }
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) c += p / static_cast<double>(points.size());
  double r = 0;
  for (const Eigen::Vector3d& p : points) r = std::max(r, (p - c).norm());
  return std::max(r, 0.05);
}

double BaseRadius(const MobileBase& base, double scale) {
  if (base.type == BaseType::kDifferential) return 0.6 * base.differential.track;
  double r = 0;
  for (const Wheel& w : base.wheels) r = std::max(r, w.distance + w.radius);
  return std::clamp(r > 0 ? r : 0.13, 0.02, std::max(0.05, 0.3 * scale));
}

// A body's meshes (scene_format.md): the file's index in the scene's
// "meshes", the mesh frame in the body frame, the scale (not rounded: a scale
// of 1e-9 is valid and must not become 0).
json BodyMeshes(const Body& body, const std::vector<int>& file_of) {
  json meshes = json::array();
  for (std::size_t i = 0; i < body.meshes.size(); ++i) {
    const BodyMesh& m = body.meshes[i];
    const Eigen::Quaterniond q(m.R_BM);
    meshes.push_back({{"file", file_of[i]},
                      {"position", Vec(m.p_BM)},
                      {"quaternion", {Round(q.x()), Round(q.y()), Round(q.z()), Round(q.w())}},
                      {"scale", {m.scale.x(), m.scale.y(), m.scale.z()}}});
  }
  return meshes;
}

// The scene's "meshes": each distinct file once, as base64 binary STL.
json MeshList(const MeshFiles& files) {
  json list = json::array();
  for (const MeshFiles::File& f : files.files) {
    list.push_back({{"path", f.path}, {"triangles", f.triangles}, {"stl_base64", Base64(f.stl)}});
  }
  return list;
}

json Bodies(const Model& model, double scale, const MeshFiles* meshes) {
  json bodies = json::array();
  for (int b = 0; b < model.num_bodies(); ++b) {
    const Body& body = model.bodies[b];
    const std::vector<Eigen::Vector3d> points = BodyPoints(model, b);
    json j = {{"name", body.name}, {"kind", "body"}};
    if (body.is_mobile_base()) {
      const MobileBase& base = model.mobile_bases[body.base_index];
      j["kind"] = base.type == BaseType::kOmni ? "omni" : "differential";
      j["radius"] = Round(BaseRadius(base, scale));
    }
    j["points"] = json::array();
    for (const Eigen::Vector3d& p : points) j["points"].push_back(Vec(p));
    j["links"] = BodyLinks(points, body.is_mobile_base());
    if (meshes != nullptr && !body.meshes.empty()) j["meshes"] = BodyMeshes(body, meshes->file_of[b]);
    bodies.push_back(j);
  }
  return bodies;
}

json Joints(const Model& model) {
  json joints = json::array();
  for (const Joint& joint : model.joints) {
    json j = {{"name", joint.name}, {"type", JointTypeName(joint.type)}, {"body", joint.body_a},
              {"point", Vec(joint.p_A)}, {"actuated", joint.actuated}};
    if (joint.type == JointType::kRevolute || joint.type == JointType::kPrismatic ||
        joint.type == JointType::kUniversal) {
      j["axis"] = Vec(joint.a_A);
    }
    joints.push_back(j);
  }
  return joints;
}

// The "workspace" object (scene_format.md): the cloud's points, flags and
// sigma_min in row order. Its values are finite by construction
// (CloudFromWorkspaceCsv), so no null can appear.
json Workspace(const WorkspaceCloud& cloud) {
  json points = json::array(), reachable = json::array(), sigma = json::array();
  for (size_t i = 0; i < cloud.points.size(); ++i) {
    points.push_back(Vec(cloud.points[i]));
    reachable.push_back(cloud.reachable[i] ? 1 : 0);
    sigma.push_back(Round(cloud.sigma_min[i]));
  }
  return {{"points", std::move(points)},   {"reachable", std::move(reachable)}, {"sigma_min", std::move(sigma)},
          {"components", cloud.components}, {"source", cloud.source}};
}

json Poses(const State& s) {
  json poses = json::array();
  for (int b = 0; b < s.num_bodies(); ++b) {
    const double* p = s.pose(b);  // [qx, qy, qz, qw, px, py, pz]
    poses.push_back({Round(p[4]), Round(p[5]), Round(p[6]), Round(p[0]), Round(p[1]), Round(p[2]), Round(p[3])});
  }
  return poses;
}

// The scene as JSON text safe inside <script>: no "</script>", "<!--" or
// entity can form (<, > and & written as JSON unicode escapes, read back unchanged).
std::string ScriptSafeJson(const json& scene) {
  const std::string text = scene.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<') out += "\\u003c";
    else if (c == '>') out += "\\u003e";
    else if (c == '&') out += "\\u0026";
    else out += c;
  }
  return out;
}

// Re-assembles frame after frame within the work bound (scene.h).
class FrameAssembler {
 public:
  FrameAssembler(const Model& model, double flag_energy) : forward_(model), flag_energy_(flag_energy) {}

  // Moves to controls u from the last frame assembled. True if assembled (E
  // at most the flag level); *jump: reached by a branch jump; *beyond: not
  // attempted, beyond the bound (the state is left as it was).
  bool Assemble(const Eigen::VectorXd& u, bool* jump, bool* beyond) {
    const double needed = SubstepsTo(u);
    *jump = false;
    *beyond = !(needed <= kMaxViewFrameSubsteps && used_ + needed <= kMaxViewSubsteps);
    if (*beyond) return false;
    const ForwardResult r = forward_.Assemble(u);
    used_ += r.substeps;
    *jump = r.branch_jump;
    return r.residual_energy <= flag_energy_;
  }
  const ForwardProblem& forward() const { return forward_; }

 private:
  // The sub-steps ForwardProblem::Assemble would take to u (the largest
  // control change, headings the short way, over max_control_step), counted
  // in double so that any distance compares without overflow.
  double SubstepsTo(const Eigen::VectorXd& u) const {
    Eigen::VectorXd change = u - forward_.controls();
    for (int k = 0; k < forward_.model().num_bases(); ++k) {
      change[kBaseControlSize * k + 2] = WrapAngle(change[kBaseControlSize * k + 2]);
    }
    return std::max(1.0, std::ceil(change.lpNorm<Eigen::Infinity>() / forward_.options().max_control_step));
  }

  ForwardProblem forward_;
  const double flag_energy_;
  long used_ = 0;  // sub-steps solved so far
};

}  // namespace

double FlagEnergyFor(const std::string& source) {
  return source == "replay" ? ReplayOptions().torn_residual_energy : ForwardOptions().assembly_tolerance;
}

std::string BuildScene(const Model& model, const std::vector<ViewFrame>& frames, const std::string& source,
                       SceneSummary* summary, const WorkspaceCloud* workspace, const MeshFiles* meshes) {
  const double scale = Scale(model, workspace);
  json scene = {{"format", "ccma-scene-1"}, {"model", model.name},    {"description", model.description},
                {"scale", Round(scale)},     {"bodies", Bodies(model, scale, meshes)}, {"joints", Joints(model)},
                {"end_effector", {{"body", model.end_effector.body}, {"point", Vec(model.end_effector.p_B)}}},
                {"source", source}};
  json time = json::array(), poses = json::array(), flags = json::array();
  json commanded = json::array(), tracked = json::array();
  json bases = json::array();
  for (int k = 0; k < model.num_bases(); ++k) bases.push_back(json::array());
  SceneSummary s;
  FrameAssembler assembler(model, FlagEnergyFor(source));
  const ForwardProblem& forward = assembler.forward();
  if (frames.empty()) {
    time.push_back(0);
    poses.push_back(Poses(forward.state()));
    flags.push_back(0);
  }
  bool any_commanded = false;
  for (const ViewFrame& f : frames) {
    bool jump = false, beyond = false;
    const bool assembled = assembler.Assemble(f.controls, &jump, &beyond);
    const bool flagged = f.flagged || !assembled || jump;
    s.not_assembled += assembled ? 0 : 1;
    s.beyond_work_bound += beyond ? 1 : 0;
    s.branch_jumps += jump ? 1 : 0;
    s.flagged_frames += flagged ? 1 : 0;
    time.push_back(Round(f.time));
    poses.push_back(Poses(forward.state()));
    flags.push_back(flagged ? 1 : 0);
    any_commanded = any_commanded || f.commanded.has_value();
    // A missing point (a failed step's empty cell) repeats the last one.
    const Eigen::Vector3d reached = forward.end_effector().position;
    commanded.push_back(Vec(f.commanded.value_or(reached)));
    tracked.push_back(Vec(f.tracked.value_or(reached)));
    for (int k = 0; k < model.num_bases(); ++k) {
      bases[k].push_back({Round(f.controls[3 * k]), Round(f.controls[3 * k + 1])});
    }
  }
  s.frames = static_cast<int>(time.size());
  scene["frames"] = {{"time", time}, {"poses", poses}, {"flags", flags}};
  if (!frames.empty()) {
    scene["paths"] = {{"tracked", tracked}, {"bases", bases}};
    if (any_commanded) scene["paths"]["commanded"] = commanded;
  }
  if (workspace != nullptr) {
    scene["workspace"] = Workspace(*workspace);
    s.workspace_points = static_cast<long>(workspace->points.size());
    s.workspace_reachable = workspace->reachable_count;
  }
  // No key without meshes: --meshes on a model that names none changes nothing.
  if (meshes != nullptr && !meshes->files.empty()) scene["meshes"] = MeshList(*meshes);
  if (summary != nullptr) *summary = s;
  return ScriptSafeJson(scene);
}

}  // namespace ccma::viewer
