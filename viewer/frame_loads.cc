#include "viewer/frame_loads.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "ccma/internal/constraint_set.h"
#include "ccma/internal/format.h"

namespace ccma::viewer {

bool HasMasses(const Model& model) {
  if (model.end_effector.payload.mass > 0) return true;
  return std::any_of(model.bodies.begin(), model.bodies.end(), [](const Body& b) { return b.inertia.mass > 0; });
}

std::vector<double> BodyLoads(const Model& model, const StaticsReport& report) {
  std::vector<double> loads(model.bodies.size(), 0.0);
  for (std::size_t j = 0; j < model.joints.size() && j < report.joints.size(); ++j) {
    const double f = report.joints[j].force.norm();
    for (const int b : {model.joints[j].body_a, model.joints[j].body_b}) {
      if (b != kWorld) loads[static_cast<std::size_t>(b)] = std::max(loads[static_cast<std::size_t>(b)], f);
    }
  }
  return loads;
}

FrameLoads::FrameLoads(const Model& model, int frames) : model_(model), masses_(HasMasses(model)) {
  if (!masses_) return;  // every load 0: nothing to solve, nothing to bound
  const ConstraintSet set(model);
  const double rows = set.num_rows(), columns = set.state_size();
  if (rows * columns > static_cast<double>(kMaxStaticsEntries)) {
    throw std::invalid_argument("statics: " + std::to_string(set.num_rows()) + " constraint rows x " +
                                std::to_string(set.state_size()) + " state coordinates exceed " +
                                std::to_string(kMaxStaticsEntries) + " entries");
  }
  const double work = frames * rows * columns * std::min(rows, columns);
  if (work > kMaxViewStaticsWork) {
    throw std::invalid_argument("statics of " + std::to_string(frames) + " frames of " +
                                std::to_string(set.num_rows()) + " constraint rows x " +
                                std::to_string(set.state_size()) + " state coordinates: beyond the work bound of " +
                                FormatG(kMaxViewStaticsWork) +
                                " (frames x rows x coordinates x the smaller of the two); view fewer frames");
  }
}

void FrameLoads::Add(const State& s, const Eigen::VectorXd& u) {
  if (!masses_) {  // no load: the reactions are all 0 (balanced, and unique as far as a load can tell)
    loads_.emplace_back(model_.bodies.size(), 0.0);
    balanced_.push_back(true);
    determinate_.push_back(true);
    return;
  }
  const StaticsReport report = ComputeStatics(model_, s, u);
  loads_.push_back(BodyLoads(model_, report));
  for (const double f : loads_.back()) max_ = std::max(max_, f);
  balanced_.push_back(report.balanced);
  determinate_.push_back(report.determinate);
}

}  // namespace ccma::viewer
