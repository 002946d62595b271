#include "documents/workspace_table.h"

#include <limits>
#include <stdexcept>

#include "analyses/compliance.h"
#include "analyses/precision.h"
#include "analyses/work_estimate.h"

namespace ccma::documents {

double WorkspaceEeStd(const Model& model, const State& s, const Eigen::VectorXd& u) {
  return EndEffectorPositionStd(model, s, u);
}

double WorkspaceStiffnessMin(const Model& model, const State& s, const Eigen::VectorXd& u) {
  return SmallestTranslationalStiffness(model, s, u);
}

WorkspaceComputedColumns ComputeWorkspaceColumns(const Model& model, const std::vector<WorkspaceSample>& samples,
                                                 const std::function<void(long long)>& on_row) {
  const auto n = static_cast<Eigen::Index>(samples.size());
  WorkspaceComputedColumns c;
  c.ee_std_m = Eigen::VectorXd::Zero(n);
  if (model.compliant()) c.stiffness_min = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const WorkspaceSample& s = samples[static_cast<std::size_t>(i)];
    if (s.reachable) {
      c.ee_std_m[i] = WorkspaceEeStd(model, s.state, s.controls);
      if (model.compliant()) c.stiffness_min[i] = WorkspaceStiffnessMin(model, s.state, s.controls);
    }
    if (on_row) on_row(i + 1);
  }
  return c;
}

double WorkspaceRowSeconds(const Model& model) {
  const State home = State::Home(model);
  const Eigen::VectorXd u = model.home_controls();
  return LeastSecondsOf([&] {
    WorkspaceEeStd(model, home, u);
    if (model.compliant()) WorkspaceStiffnessMin(model, home, u);
  });
}

namespace {

// A column of one number per sample.
template <typename F>
void AddColumn(Table* t, const char* name, ColumnKind kind, const std::vector<WorkspaceSample>& samples, F value) {
  std::vector<double>& v = t->Add(name, kind).values;
  v.reserve(samples.size());
  for (const WorkspaceSample& s : samples) v.push_back(value(s));
}

}  // namespace

Table WorkspaceTable(const Model& model, const std::vector<WorkspaceSample>& samples,
                     const WorkspaceComputedColumns& computed) {
  const auto n = static_cast<Eigen::Index>(samples.size());
  if (computed.ee_std_m.size() != n || (model.compliant() && computed.stiffness_min.size() != n)) {
    throw std::invalid_argument("workspace table: the computed columns have another length than the samples");
  }
  Table t;
  for (int c = 0; c < 6; ++c) {
    if (!model.end_effector.controlled[static_cast<std::size_t>(c)]) continue;
    AddColumn(&t, kEndEffectorComponentNames[static_cast<std::size_t>(c)], ColumnKind::kNumber, samples,
              [c](const WorkspaceSample& s) { return c < 3 ? s.pose.position[c] : s.pose.rpy[c - 3]; });
  }
  AddColumn(&t, "reachable", ColumnKind::kFlag, samples, [](const WorkspaceSample& s) { return s.reachable ? 1.0 : 0.0; });
  AddColumn(&t, "residual_energy", ColumnKind::kNumber, samples, [](const WorkspaceSample& s) { return s.residual_energy; });
  AddColumn(&t, "sigma_min", ColumnKind::kNumber, samples,
            [](const WorkspaceSample& s) { return s.reachable ? s.sigma_min : 0.0; });
  AddColumn(&t, "error", ColumnKind::kNumber, samples, [](const WorkspaceSample& s) { return s.error; });
  AddColumn(&t, "rcond", ColumnKind::kNumber, samples, [](const WorkspaceSample& s) { return s.rcond; });
  AddColumn(&t, "max_limit_violation", ColumnKind::kNumber, samples,
            [](const WorkspaceSample& s) { return s.max_limit_violation; });
  std::vector<std::string>& limited = t.Add("limited_by", ColumnKind::kText).texts;
  for (const WorkspaceSample& s : samples) limited.push_back(s.limited_by);
  AddColumn(&t, "wave", ColumnKind::kCount, samples, [](const WorkspaceSample& s) { return double(s.wave); });
  AddColumn(&t, "start", ColumnKind::kCount, samples, [](const WorkspaceSample& s) { return double(s.start); });
  std::vector<double>& ee_std = t.Add("ee_std_m").values;
  std::vector<double>* stiffness = model.compliant() ? &t.Add("stiffness_min_N_per_m").values : nullptr;
  for (Eigen::Index i = 0; i < n; ++i) {
    const bool reached = samples[static_cast<std::size_t>(i)].reachable;
    ee_std.push_back(reached ? computed.ee_std_m[i] : 0.0);
    if (stiffness) stiffness->push_back(reached ? computed.stiffness_min[i] : 0.0);
  }
  for (int k = 0; k < model.num_controls(); ++k) {
    AddColumn(&t, ("u" + std::to_string(k)).c_str(), ColumnKind::kNumber, samples, [k](const WorkspaceSample& s) {
      return s.reachable ? s.controls[k] : std::numeric_limits<double>::quiet_NaN();
    });
  }
  return t;
}

}  // namespace ccma::documents
