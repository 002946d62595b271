// `type: differential`: two driven wheels on one axle. It assembles like an
// omni base with complete actuation; that it cannot slide sideways is a
// constraint on motions between control vectors, not on a configuration
// (problems/internal/differential_arc_constraint.h, differential_turning.h).
#include "ccma/bases/base_kinds.h"
#include "ccma/bases/wheeled_base.h"
#include "ccma/model.h"

namespace ccma {
namespace {

class DifferentialBaseKind final : public BaseKind {
 public:
  const char* name() const override { return "differential"; }
  const std::vector<BaseControl>& controls() const override { return internal::WheeledBaseControls(); }
  std::vector<BaseConstraint> Constraints(const MobileBase& /*base*/, bool autodiff) const override {
    return internal::WheeledBaseConstraints(autodiff);
  }
  int num_residuals() const override { return internal::WheeledBaseResidualCount(); }
};

}  // namespace

const BaseKind& DifferentialBase() {
  static const DifferentialBaseKind kind;
  return kind;
}

}  // namespace ccma
