// The inertia of a moving mechanism as loads (d'Alembert), and its energies,
// for inverse dynamics (analyses/dynamics.h).
//
// Motion is given over the state tangent (state.h), per body b:
//   velocity[6b..]     = [omega; v]     angular velocity [rad/s] and velocity
//                                        of the body's origin [m/s], world
//   acceleration[6b..] = [alpha; a]     their rates [rad/s^2, m/s^2]
// (the first and second derivatives of the chart R <- Exp(dphi) R,
// p <- p + dp centred at the configuration: exactly these). Every mass of
// the model (bodies' `mass`, `com`, `inertia` and the payload) contributes;
// a body without `inertia` is a point mass at its `com`.
// Units: N, N*m, J.
#ifndef CCMA_INERTIAL_LOADS_H_
#define CCMA_INERTIAL_LOADS_H_

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// The inertial loads Q_in (s.tangent_size()), in the layout of
// GeneralizedLoads (loads.h: per body [M about its origin; F], world):
//   F = -m a_c,   M = r x F - (I alpha + omega x I omega)
// with r = R com_B, a_c = a + alpha x r + omega x (omega x r) and I the
// inertia about the centre of mass in world axes. GeneralizedLoads + Q_in
// are the loads the constraints and the controls hold while it moves.
Eigen::VectorXd InertialLoads(const Model& model, const State& s, const Eigen::VectorXd& velocity,
                              const Eigen::VectorXd& acceleration);

// Kinetic energy sum 1/2 m |v_c|^2 + 1/2 omega . I omega [J].
double KineticEnergy(const Model& model, const State& s, const Eigen::VectorXd& velocity);

// Potential energy of gravity, -sum m g . c over every mass's centre c [J]
// (zero where c = 0).
double PotentialEnergy(const Model& model, const State& s);

}  // namespace ccma

#endif  // CCMA_INERTIAL_LOADS_H_
