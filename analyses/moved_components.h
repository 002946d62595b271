// Which components of the end-effector pose X = (x, y, z, roll, pitch, yaw)
// (model_format.md, "End-effector pose") the controls move at a
// configuration: the default of `ccma import --controlled`, and its check
// of a given list (docs/import.md, "Controlled components").
//
// The motions counted are those of `ccma check`'s end_effector_dof
// (analyses/mobility.h): (ds, du_eff) with dC/ds ds + dC/du du = 0, the
// constraints held and the effective controls free; their images under
// dX/ds form a 6 x m matrix Y. Wherever the controls determine the state,
// Y spans the columns of dX/du. The rank of a set of components is the rank
// of its rows of Y.
#ifndef CCMA_ANALYSES_MOVED_COMPONENTS_H_
#define CCMA_ANALYSES_MOVED_COMPONENTS_H_

#include <array>

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// Relative rank tolerance: a singular value counts when it is above
// kMovedComponentTolerance times max(1, the largest singular value) of the
// matrix ranked (dC/ds for the motions, Y for the components), as
// AnalyzeMobility's default. Y's entries are metres or radians per unit
// motion, so 1e-8 is far below any component a joint moves and far above
// the rounding of a null-space basis (about 1e-13).
constexpr double kMovedComponentTolerance = 1e-8;

// x y z roll pitch yaw, as EndEffector::controlled.
using ComponentSet = std::array<bool, 6>;

struct MovedComponents {
  // The components chosen: x, y, z, roll, pitch, yaw in this order, each
  // kept when it raises the rank of the rows kept before it. Translations
  // come first, so a planar mechanism gets its two in-plane translations.
  ComponentSet chosen{};
  int rank = 0;        // rank of all six rows of Y = the count of `chosen`
  int given_rank = 0;  // rank of the rows of `given` (as passed in)
};

// The analysis at state s and controls u. Dense up to kDenseMobilityStateSize
// (a column-pivoting QR for the motions, an SVD for Y's rows), sparse
// rank-revealing QR beyond (rank([A; X_S]) -
// rank(A), A = [dC/ds, dC/du_eff]), as AnalyzeMobility. Throws
// std::invalid_argument above kMaxMobilityStateSize.
MovedComponents AnalyzeMovedComponents(const Model& model, const State& s, const Eigen::VectorXd& u,
                                       const ComponentSet& given, double rank_tolerance = kMovedComponentTolerance);

}  // namespace ccma

#endif  // CCMA_ANALYSES_MOVED_COMPONENTS_H_
