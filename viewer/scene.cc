#include "viewer/scene.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>

#include "ccma/rotation.h"
#include "collision/clearance.h"
#include "collision/collision_model.h"
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
  if (base.type == BaseType::kLegged) return base.legged.footprint.x() > 0 ? 0.5 * base.legged.footprint.norm() : 0.3;
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

// The scene's "meshes": each distinct file once, as base64 binary STL, named
// by its page path (never absolute: the page is passed on to others).
json MeshList(const MeshFiles& files) {
  json list = json::array();
  for (const MeshFiles::File& f : files.files) {
    list.push_back({{"path", f.page_path}, {"triangles", f.triangles}, {"stl_base64", Base64(f.stl)}});
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
      j["kind"] = KindOf(base).name();
      j["radius"] = Round(BaseRadius(base, scale));
      if (base.type == BaseType::kLegged) {
        // Without a footprint, a body box of a typical quadruped's proportions.
        const Eigen::Vector2d box = base.legged.footprint.x() > 0 ? base.legged.footprint : Eigen::Vector2d(0.6, 0.3);
        j["footprint"] = {Round(box.x()), Round(box.y())};
        j["body_height"] = Round(base.legged.height);
      }
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

// The "workspace" object (scene_format.md) as JSON text: the cloud's
// points, flags and sigma_min in row order, each number as nlohmann::json
// writes it. Written straight to text: a tree of a million points would take
// ~150 MB, and nlohmann::json allocates while it destroys one (a failed
// allocation there ends the process instead of throwing). Its values are
// finite by construction (CloudFromWorkspaceCsv), so no null can appear.
std::string WorkspaceText(const WorkspaceCloud& cloud) {
  const auto number = [](double v) { return json(Round(v)).dump(); };
  std::string points, reachable, sigma;
  for (size_t i = 0; i < cloud.points.size(); ++i) {
    const char* comma = i == 0 ? "" : ",";
    const Eigen::Vector3d& p = cloud.points[i];
    points += comma + ("[" + number(p.x()) + "," + number(p.y()) + "," + number(p.z()) + "]");
    reachable += comma + std::string(cloud.reachable[i] ? "1" : "0");
    sigma += comma + number(cloud.sigma_min[i]);
  }
  const json names = {{"components", cloud.components}, {"source", cloud.source}};
  return "{\"components\":" + names["components"].dump(-1, ' ', false, json::error_handler_t::replace) +
         ",\"points\":[" + points + "],\"reachable\":[" + reachable + "],\"sigma_min\":[" + sigma +
         "],\"source\":" + names["source"].dump(-1, ' ', false, json::error_handler_t::replace) + "}";
}

// The "collision" object (scene_format.md): the shapes as the model gives
// them. Capsules stay in their body's frame and obstacles in the world, so
// the page poses them with the bodies' poses alone; a base's cylinder
// follows its body's x and y (collision_model.h).
json Collision(const Model& model) {
  const CollisionGeometry& g = model.collision;
  json bases = json::array(), base_bodies = json::array(), links = json::array(), obstacles = json::array();
  for (int k = 0; k < model.num_bases(); ++k) {
    bases.push_back(Round(g.base_radii.empty() ? g.base_radius : g.base_radii[static_cast<size_t>(k)]));
    base_bodies.push_back(model.mobile_bases[k].body);
  }
  for (const CollisionCapsule& c : g.links) {
    links.push_back({{"body", c.body}, {"from", Vec(c.a_B)}, {"to", Vec(c.b_B)}, {"radius", Round(c.radius)}});
  }
  for (const Obstacle& o : g.obstacles) {
    // The centre of the shape: a cylinder's z is half-way up (the model's own centre has no z).
    const Eigen::Vector3d center(o.center.x(), o.center.y(), 0.5 * (o.z_min + o.z_max));
    json j = {{"name", o.name}, {"center", Vec(center)}, {"z_min", Round(o.z_min)}, {"z_max", Round(o.z_max)}};
    if (o.shape == ObstacleShape::kCylinder) {
      j["shape"] = "cylinder";
      j["radius"] = Round(o.radius);
    } else {
      j["shape"] = "box";
      j["size"] = Vec(o.size);
      j["yaw"] = Round(o.yaw);
    }
    obstacles.push_back(j);
  }
  return {{"margin", Round(g.margin)}, {"base_height", Round(g.base_height)}, {"bases", std::move(bases)},
          {"base_bodies", std::move(base_bodies)}, {"links", std::move(links)}, {"obstacles", std::move(obstacles)}};
}

// Each frame's smallest clearance and its pair (frames.clearance,
// frames.clearance_pairs), for a model with collision geometry in which
// some pair is checked; nothing otherwise.
class ClearanceColumns {
 public:
  ClearanceColumns(const Model& model, const State& home) {
    if (!model.collision.enabled) return;
    collision_.emplace(model);
    active_ = MinimumClearance(*collision_, home).any;  // which pairs are checked does not depend on the state
  }

  // Records the clearance at s; true when it is below the margin (the frame is flagged).
  bool Add(const State& s) {
    if (!active_) return false;
    const ClearanceSummary c = MinimumClearance(*collision_, s);
    clearance_.push_back(Round(c.min));
    pairs_.push_back({c.a, c.b});
    return c.min < collision_->margin() - 1e-9;
  }

  void WriteTo(json* frames) const {
    if (!active_) return;
    (*frames)["clearance"] = clearance_;
    (*frames)["clearance_pairs"] = pairs_;
  }

 private:
  std::optional<CollisionModel> collision_;
  bool active_ = false;
  json clearance_ = json::array(), pairs_ = json::array();
};

json Poses(const State& s) {
  json poses = json::array();
  for (int b = 0; b < s.num_bodies(); ++b) {
    const double* p = s.pose(b);  // [qx, qy, qz, qw, px, py, pz]
    poses.push_back({Round(p[4]), Round(p[5]), Round(p[6]), Round(p[0]), Round(p[1]), Round(p[2]), Round(p[3])});
  }
  return poses;
}

// JSON text made safe inside <script>: no "</script>", "<!--" or entity can
// form (<, > and & written as JSON unicode escapes, read back unchanged).
std::string ScriptSafe(const std::string& text) {
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
      const int heading = forward_.model().base_control(k) + kBaseHeading;
      change[heading] = WrapAngle(change[heading]);
    }
    return std::max(1.0, std::ceil(change.lpNorm<Eigen::Infinity>() / forward_.options().max_control_step));
  }

  ForwardProblem forward_;
  const double flag_energy_;
  long used_ = 0;  // sub-steps solved so far
};

// The per-frame columns of the scene ("frames" and "paths").
struct SceneFrameColumns {
  json time = json::array(), poses = json::array(), flags = json::array();
  json commanded = json::array(), tracked = json::array(), bases = json::array();  // bases: one list per base
  bool any_commanded = false;
};

// Re-assembles the frames in turn (scene.h), filling the columns, the
// clearance and the summary's counts.
void AddFrames(const Model& model, const std::vector<ViewFrame>& frames, FrameAssembler* assembler,
               ClearanceColumns* clearance, FrameLoads* loads, SceneFrameColumns* c, SceneSummary* s) {
  const ForwardProblem& forward = assembler->forward();
  for (const ViewFrame& f : frames) {
    bool jump = false, beyond = false;
    const bool assembled = assembler->Assemble(f.controls, &jump, &beyond);
    const bool below = clearance->Add(forward.state());  // at the state drawn
    if (loads != nullptr) loads->Add(forward.state(), forward.controls());
    const bool flagged = f.flagged || !assembled || jump || below;
    s->not_assembled += assembled ? 0 : 1;
    s->beyond_work_bound += beyond ? 1 : 0;
    s->branch_jumps += jump ? 1 : 0;
    s->clearance_below_margin += below ? 1 : 0;
    s->flagged_frames += flagged ? 1 : 0;
    c->time.push_back(Round(f.time));
    c->poses.push_back(Poses(forward.state()));
    c->flags.push_back(flagged ? 1 : 0);
    c->any_commanded = c->any_commanded || f.commanded.has_value();
    // A missing point (a failed step's empty cell) repeats the last one.
    const Eigen::Vector3d reached = forward.end_effector().position;
    c->commanded.push_back(Vec(f.commanded.value_or(reached)));
    c->tracked.push_back(Vec(f.tracked.value_or(reached)));
    for (int k = 0; k < model.num_bases(); ++k) {
      const int first = model.base_control(k);
      c->bases[k].push_back({Round(f.controls[first]), Round(f.controls[first + 1])});
    }
  }
}

// The "loads" object (scene_format.md) and its counts in the summary.
json Loads(const FrameLoads& loads, SceneSummary* s) {
  json per_frame = json::array(), balanced = json::array(), determinate = json::array();
  for (std::size_t f = 0; f < loads.body_loads().size(); ++f) {
    json row = json::array();
    for (const double load : loads.body_loads()[f]) row.push_back(Round(load));
    per_frame.push_back(std::move(row));
    balanced.push_back(loads.balanced()[f] ? 1 : 0);
    determinate.push_back(loads.determinate()[f] ? 1 : 0);
    s->unbalanced_frames += loads.balanced()[f] ? 0 : 1;
    s->indeterminate_frames += loads.determinate()[f] ? 0 : 1;
  }
  s->max_load = loads.max();
  return {{"quantity", "joint_reaction_force"}, {"unit", "N"},           {"masses", loads.masses()},
          {"max", Round(loads.max())},          {"body_loads", per_frame}, {"balanced", balanced},
          {"determinate", determinate}};
}

// Deflections are micrometres: their numbers keep 1e-12 (m or rad).
double SceneRoundFine(double v) { return std::round(v * 1e12) / 1e12; }

json ScenePoseRow(const Eigen::Vector3d& p, const Eigen::Quaterniond& q, double (*round)(double)) {
  return {round(p.x()), round(p.y()), round(p.z()), round(q.x()), round(q.y()), round(q.z()), round(q.w())};
}

// The "deflection" object (scene_format.md) of the loaded shape at the
// state drawn (the scene's only frame).
json SceneDeflection(const Model& model, const DeflectedShape& shape) {
  const State& loaded = shape.equilibrium.state;
  json drawn = json::array(), loaded_poses = json::array(), body = json::array(), ee = json::array();
  for (int b = 0; b < model.num_bodies(); ++b) {
    drawn.push_back(ScenePoseRow(shape.p_WB_drawn[b], shape.q_WB_drawn[b], Round));
    loaded_poses.push_back(ScenePoseRow(loaded.p_WB(b), loaded.q_WB(b), SceneRoundFine));
    body.push_back(SceneRoundFine(shape.body_deflection_m[b]));
  }
  for (int i = 0; i < 6; ++i) ee.push_back(SceneRoundFine(shape.equilibrium.deflection[i]));
  return {{"scale", shape.scale},
          {"unit", "m"},
          {"poses", std::move(drawn)},
          {"loaded_poses", std::move(loaded_poses)},
          {"body_deflection", std::move(body)},
          {"max", SceneRoundFine(shape.max_deflection_m)},
          {"max_body", shape.max_body},
          {"end_effector", std::move(ee)},
          {"converged", shape.equilibrium.converged},
          {"held", shape.equilibrium.held},
          {"load_fraction", SceneRoundFine(shape.equilibrium.load_fraction)}};
}

}  // namespace

double FlagEnergyFor(const std::string& source) {
  return source == "replay" ? ReplayOptions().torn_residual_energy : ForwardOptions().assembly_tolerance;
}

std::string BuildScene(const Model& model, const std::vector<ViewFrame>& frames, const std::string& source,
                       SceneSummary* summary, const WorkspaceCloud* workspace, const MeshFiles* meshes,
                       ColorBy color_by, const DeflectionRequest* deflection, const FrameEfforts* efforts) {
  const double scale = Scale(model, workspace);
  json scene = {{"format", "ccma-scene-1"}, {"model", model.name},    {"description", model.description},
                {"scale", Round(scale)},     {"bodies", Bodies(model, scale, meshes)}, {"joints", Joints(model)},
                {"end_effector", {{"body", model.end_effector.body}, {"point", Vec(model.end_effector.p_B)}}},
                {"source", source}};
  SceneSummary s;
  std::optional<FrameLoads> loads;  // bounded before any frame is assembled
  if (color_by == ColorBy::kLoad) loads.emplace(model, frames.empty() ? 1 : static_cast<int>(frames.size()));
  FrameAssembler assembler(model, FlagEnergyFor(source));
  ClearanceColumns clearance(model, assembler.forward().state());
  SceneFrameColumns c;
  for (int k = 0; k < model.num_bases(); ++k) c.bases.push_back(json::array());
  if (frames.empty()) {  // the model at home
    const bool below = clearance.Add(assembler.forward().state());
    if (loads) loads->Add(assembler.forward().state(), assembler.forward().controls());
    c.time.push_back(0);
    c.poses.push_back(Poses(assembler.forward().state()));
    c.flags.push_back(below ? 1 : 0);
    s.clearance_below_margin += below ? 1 : 0;
    s.flagged_frames += below ? 1 : 0;
  }
  AddFrames(model, frames, &assembler, &clearance, loads ? &*loads : nullptr, &c, &s);
  s.frames = static_cast<int>(c.time.size());
  scene["frames"] = {{"time", c.time}, {"poses", c.poses}, {"flags", c.flags}};
  clearance.WriteTo(&scene["frames"]);
  if (!frames.empty()) {
    scene["paths"] = {{"tracked", c.tracked}, {"bases", c.bases}};
    if (c.any_commanded) scene["paths"]["commanded"] = c.commanded;
  }
  // No key without collision geometry: the scene of any other model is as it was.
  if (model.collision.enabled) scene["collision"] = Collision(model);
  if (loads) scene["loads"] = Loads(*loads, &s);  // no key unless colouring by load
  if (efforts != nullptr) {  // no key unless --dynamics
    scene["efforts"] = FrameEffortsJson(*efforts);
    s.max_effort_share = efforts->max;
    for (const std::vector<double>& row : efforts->shares) {
      s.effort_frames_beyond_limit += std::any_of(row.begin(), row.end(), [](double x) { return x > 1 + 1e-9; });
    }
  }
  if (deflection != nullptr) {  // a static view: the state drawn is its only frame's
    if (s.not_assembled > 0) throw DeflectionError("the mechanism is not assembled at these controls");
    const ForwardProblem& forward = assembler.forward();
    s.deflected = ComputeDeflectedShape(model, forward.state(), forward.controls(), *deflection);
    scene["deflection"] = SceneDeflection(model, *s.deflected);
  }
  // No key without meshes: --meshes on a model that names none changes nothing.
  if (meshes != nullptr && !meshes->files.empty()) scene["meshes"] = MeshList(*meshes);
  std::string text = scene.dump(-1, ' ', false, json::error_handler_t::replace);
  if (workspace != nullptr) {  // the last key in nlohmann's (sorted) order
    text.pop_back();
    text += ",\"workspace\":" + WorkspaceText(*workspace) + "}";
    s.workspace_points = static_cast<long>(workspace->points.size());
    s.workspace_reachable = workspace->reachable_count;
  }
  if (summary != nullptr) *summary = s;
  return ScriptSafe(text);
}

}  // namespace ccma::viewer
