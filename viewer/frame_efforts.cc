#include "viewer/frame_efforts.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "analyses/internal/motion_limits.h"
#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "viewer/csv_reader.h"

namespace ccma::viewer {
namespace {

using internal::MotionLimit;

// The body a limit's actuator drives.
int DrivenBody(const Model& model, const MotionLimit& limit) {
  for (const Joint& joint : model.joints) {
    if (joint.name == limit.name && limit.kind == MotionLimit::Kind::kEffort) {
      return joint.body_b != kWorld ? joint.body_b : joint.body_a;
    }
  }
  for (const MobileBase& base : model.mobile_bases) {
    if (base.name == limit.name) return base.body;
  }
  return -1;
}

double Rounded(double x) { return std::round(x * 1e7) / 1e7; }

}  // namespace

FrameEfforts ReadFrameEfforts(const Model& model, const std::string& path, const std::vector<ViewFrame>& frames) {
  std::vector<MotionLimit> limits;
  FrameEfforts out;
  for (const MotionLimit& limit : internal::MotionLimits(model)) {
    if (limit.kind == MotionLimit::Kind::kVelocity) continue;
    limits.push_back(limit);
    out.actuators.push_back({limit.name, internal::KindName(limit.kind), DrivenBody(model, limit)});
  }
  if (limits.empty()) throw std::invalid_argument("the model has no effort_limits or push_limit to judge efforts by");
  const std::vector<std::string> names = EffortColumns(model);
  std::vector<std::string> columns = {"time_s"};
  columns.insert(columns.end(), names.begin(), names.end());
  CsvReader csv(path, CsvLimits{kMaxViewFileBytes, kMaxPathSteps + 1, {}}, columns);
  const int time = csv.Find("time_s", true);
  std::vector<int> effort;
  for (const std::string& name : names) effort.push_back(csv.Find(name, true));
  size_t f = 0;
  Eigen::VectorXd e(model.num_controls());
  const Eigen::VectorXd no_rates = Eigen::VectorXd::Zero(model.num_controls());
  while (f < frames.size() && csv.Next()) {
    const double t = csv.Cell(time), tolerance = 1e-9 * (1 + std::abs(frames[f].time));
    if (std::isnan(t)) throw ViewInputError(csv.Where(time) + ": an empty time");
    if (t < frames[f].time - tolerance) continue;  // a row thinned away
    if (t > frames[f].time + tolerance) break;      // frame f has no row
    bool assembled = true;
    for (size_t c = 0; c < effort.size(); ++c) {
      e[static_cast<Eigen::Index>(c)] = csv.Cell(effort[c]);
      assembled = assembled && !std::isnan(e[static_cast<Eigen::Index>(c)]);
    }
    std::vector<double> row;
    for (const MotionLimit& limit : limits) {
      // An effort limit whose end is 0 gives +inf beyond it: shown as far beyond (1e6).
      const double share = assembled ? std::min(internal::Utilisation(limit, e, no_rates), 1e6) : -1.0;
      row.push_back(share);
      out.max = std::max(out.max, share);
    }
    out.shares.push_back(std::move(row));
    ++f;
  }
  if (f < frames.size()) {
    throw ViewInputError(path + ": no row at time_s " + FormatG(frames[f].time) +
                         " of the trajectory drawn (the dynamics of another trajectory?)");
  }
  return out;
}

nlohmann::json FrameEffortsJson(const FrameEfforts& efforts) {
  nlohmann::json actuators = nlohmann::json::array(), shares = nlohmann::json::array();
  for (const LimitedActuator& a : efforts.actuators) {
    actuators.push_back({{"name", a.name}, {"kind", a.kind}, {"body", a.body}});
  }
  for (const std::vector<double>& row : efforts.shares) {
    nlohmann::json r = nlohmann::json::array();
    for (const double x : row) r.push_back(Rounded(x));
    shares.push_back(std::move(r));
  }
  return {{"quantity", "effort_share_of_limit"}, {"actuators", actuators}, {"shares", shares},
          {"max", Rounded(efforts.max)}};
}

}  // namespace ccma::viewer
