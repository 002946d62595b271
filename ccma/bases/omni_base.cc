// `type: omni` (the default): an omnidirectional base, holonomic on the
// floor. With `actuation: reduced` its heading is held at the value in u and
// the control solver never changes it (docs/model_format.md).
#include "ccma/bases/base_kinds.h"
#include "ccma/bases/wheeled_base.h"
#include "ccma/model.h"

namespace ccma {
namespace {

class OmniBaseKind final : public internal::WheeledBaseKind {
 public:
  const char* name() const override { return "omni"; }
  bool IsEffective(const MobileBase& base, int i) const override {
    return i != kBaseHeading || base.actuation == Actuation::kComplete;
  }
};

}  // namespace

const BaseKind& OmniBase() {
  static const OmniBaseKind kind;
  return kind;
}

}  // namespace ccma
