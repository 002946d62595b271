// `type: omni` (the default): an omnidirectional base, holonomic on the
// floor. With `actuation: reduced` its heading is held at the value in u and
// the control solver never changes it (docs/model_format.md).
#include "ccma/bases/base_kinds.h"
#include "ccma/bases/wheeled_base.h"
#include "ccma/model.h"

namespace ccma {
namespace {

class OmniBaseKind final : public BaseKind {
 public:
  const char* name() const override { return "omni"; }
  const std::vector<BaseControl>& controls() const override { return internal::WheeledBaseControls(); }
  bool IsEffective(const MobileBase& base, int i) const override {
    return i != kBaseHeading || base.actuation == Actuation::kComplete;
  }
  std::vector<BaseConstraint> Constraints(const MobileBase& /*base*/, bool autodiff) const override {
    return internal::WheeledBaseConstraints(autodiff);
  }
  int num_residuals() const override { return internal::WheeledBaseResidualCount(); }
};

}  // namespace

const BaseKind& OmniBase() {
  static const OmniBaseKind kind;
  return kind;
}

}  // namespace ccma
