// Every mass of a model, where it sits: each body's `mass` and the
// end-effector's `payload` (a second mass on the end-effector body), for the
// loads statics weighs (ccma/loads.cc) and the inertia dynamics turns
// (ccma/inertial_loads.cc).
#ifndef CCMA_INTERNAL_MASSES_H_
#define CCMA_INTERNAL_MASSES_H_

#include "ccma/mass_properties.h"
#include "ccma/model.h"

namespace ccma::internal {

// fn(body index, const MassProperties&) for every mass > 0.
template <typename Fn>
void ForEachMass(const Model& model, const Fn& fn) {
  for (int b = 0; b < model.num_bodies(); ++b) {
    const MassProperties& m = model.bodies[static_cast<size_t>(b)].inertia;
    if (m.mass > 0) fn(b, m);
  }
  const MassProperties& payload = model.end_effector.payload;
  if (payload.mass > 0) fn(model.end_effector.body, payload);
}

}  // namespace ccma::internal

#endif  // CCMA_INTERNAL_MASSES_H_
