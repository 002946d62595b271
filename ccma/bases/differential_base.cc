// `type: differential`: two driven wheels on one axle. It assembles like an
// omni base with complete actuation; that it cannot slide sideways is a
// constraint on motions between control vectors, not on a configuration
// (problems/internal/differential_arc_constraint.h, differential_turning.h).
#include "ccma/bases/base_kinds.h"
#include "ccma/bases/wheeled_base.h"
#include "ccma/model.h"

namespace ccma {
namespace {

class DifferentialBaseKind final : public internal::WheeledBaseKind {
 public:
  const char* name() const override { return "differential"; }
};

}  // namespace

const BaseKind& DifferentialBase() {
  static const DifferentialBaseKind kind;
  return kind;
}

}  // namespace ccma
