#include "problems/internal/loaded_tolerances.h"

#include <algorithm>

namespace ccma {

LoadedTolerances LoadedTolerancesFor(const Model& model, const State& rigid, const ExternalWrench& wrench,
                                     double force_tolerance) {
  LoadedTolerances out;
  const Eigen::VectorXd Q = GeneralizedLoads(model, rigid, wrench);
  out.force = force_tolerance * (1 + (Q.size() > 0 ? Q.lpNorm<Eigen::Infinity>() : 0.0));
  double size = 0;
  for (int b = 0; b < rigid.num_bodies(); ++b) size = std::max(size, rigid.p_WB(b).norm());
  out.step = kLoadedStepTolerance * (1 + size);
  return out;
}

}  // namespace ccma
