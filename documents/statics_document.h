// The document of `ccma statics` (docs/cli.md) and Python's `statics()`:
// the joint reactions and control efforts of a configuration under gravity,
// the payload and a wrench (analyses/statics.h), its compliance, the
// end-effector's covariance under motion-capture noise, the payload
// capacity, the clearance, and the warnings.
#ifndef CCMA_DOCUMENTS_STATICS_DOCUMENT_H_
#define CCMA_DOCUMENTS_STATICS_DOCUMENT_H_

#include <Eigen/Core>

#include "ccma/ccma.h"
#include "documents/document.h"

namespace ccma::documents {

// At the configuration (s, u), assembled or not with residual energy
// `residual_energy` [m^2], under `wrench`, with the bases' pose noise
// `noise`. Document::warnings: the payload capacity's note, the clearance's
// when below the margin, then the "warning". Throws std::invalid_argument as
// ComputeStatics does.
Document StaticsDocument(const Model& model, const State& s, const Eigen::VectorXd& u, bool assembled,
                         double residual_energy, const ExternalWrench& wrench, const BasePoseNoise& noise);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_STATICS_DOCUMENT_H_
