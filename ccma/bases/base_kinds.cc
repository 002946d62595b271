// The registry of base types, and the defaults of BaseKind. A new base type:
// a file in this folder, its BaseType, and one line in Registered().
#include <array>
#include <utility>

#include <ceres/cost_function.h>

#include "ccma/bases/base_kinds.h"
#include "ccma/model.h"
#include "ccma/rotation.h"

namespace ccma {
namespace {

using Entry = std::pair<BaseType, const BaseKind*>;

const std::array<Entry, 3>& Registered() {
  static const std::array<Entry, 3> kinds = {Entry{BaseType::kOmni, &OmniBase()},
                                             Entry{BaseType::kDifferential, &DifferentialBase()},
                                             Entry{BaseType::kLegged, &LeggedBase()}};
  return kinds;
}

}  // namespace

Eigen::VectorXd BaseKind::HomeControls(const MobileBase& base) const { return base.home_pose; }

void BaseKind::HomeFrame(const MobileBase& base, Eigen::Matrix3d* R_WB, Eigen::Vector3d* p_WB) const {
  *R_WB = RotationZ(base.home_pose.z());
  *p_WB = Eigen::Vector3d(base.home_pose.x(), base.home_pose.y(), 0.0);
}

std::vector<ControlRange> BaseKind::Limits(const MobileBase& /*base*/) const {
  return std::vector<ControlRange>(static_cast<size_t>(num_controls()));
}

std::vector<BaseEffort> BaseKind::Efforts(const double* /*u*/, const double* effort) const {
  std::vector<BaseEffort> out;
  for (int i = 0; i < num_controls(); ++i) out.push_back({std::string("base_") + controls()[static_cast<size_t>(i)].name, effort[i]});
  return out;
}

const BaseKind& KindOf(const MobileBase& base) {
  for (const Entry& entry : Registered()) {
    if (entry.first == base.type) return *entry.second;
  }
  return OmniBase();
}

const BaseKind* FindBaseKind(const std::string& name, BaseType* type) {
  for (const Entry& entry : Registered()) {
    if (name == entry.second->name()) {
      *type = entry.first;
      return entry.second;
    }
  }
  return nullptr;
}

std::string KnownBaseKinds() {
  std::string known;
  for (const Entry& entry : Registered()) known += (known.empty() ? "" : ", ") + std::string(entry.second->name());
  return known;
}

}  // namespace ccma
