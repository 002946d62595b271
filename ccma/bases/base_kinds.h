// The registered base types (ccma/base_kind.h): one function per type, each
// defined in its own file of this folder.
#ifndef CCMA_BASES_BASE_KINDS_H_
#define CCMA_BASES_BASE_KINDS_H_

#include "ccma/base_kind.h"

namespace ccma {

const BaseKind& OmniBase();          // omni_base.cc
const BaseKind& DifferentialBase();  // differential_base.cc
const BaseKind& LeggedBase();        // legged_base.cc

// The wrench a legged body exerts on the chain, [moment about the body
// origin (N*m); force (N)] in world axes, from the generalized efforts of its
// six controls (effort = A^T wrench, A the body twist per control change) at
// its control block u. At pitch = +-pi/2 (no moment determined) the moment
// is zero.
Eigen::Matrix<double, 6, 1> LeggedBodyWrench(const double* u, const double* effort);

}  // namespace ccma

#endif  // CCMA_BASES_BASE_KINDS_H_
