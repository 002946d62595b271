// The document of `ccma simulate` (docs/cli.md) and of Python's forward
// results (`assemble`, `solve`: their to_dict() and `warning`).
#ifndef CCMA_DOCUMENTS_SIMULATE_DOCUMENT_H_
#define CCMA_DOCUMENTS_SIMULATE_DOCUMENT_H_

#include <optional>
#include <string>

#include <Eigen/Core>

#include "ccma/ccma.h"
#include "documents/document.h"

namespace ccma::documents {

// A forward solve's result and where it left the mechanism.
struct ForwardSolution : ForwardResult {
  EndEffectorPose end_effector;  // at `state`
  Eigen::VectorXd controls;
  // The model solved (it outlives the solution: the CLI's, or the problem a
  // Python result keeps alive).
  const Model* model = nullptr;
  State state;                    // the configuration after the solve
  double assembly_tolerance = 0;  // of the problem's options [m^2]
  std::string start;              // "home", "current" (Python) or the --from document's path
  // The loaded equilibrium at the rigid assembly (`simulate --loaded`,
  // Python's assemble(loaded=True)); the document's end_effector, bodies,
  // joints, limits and clearance are then the loaded configuration's.
  std::optional<LoadedEquilibrium> loaded;
};

// The solution `problem` holds after returning `result`.
ForwardSolution MakeForwardSolution(const ForwardProblem& problem, const ForwardResult& result,
                                    const std::string& start);

// The document's "warning": joints outside their limits, not assembled or
// not converged, a branch jump, a loaded equilibrium not found; "" when none.
std::string SimulateWarning(const ForwardSolution& s);

// Document::warnings: the clearance's when below the margin, the rigid
// solve's warning, then the loaded equilibrium's (the JSON joins the last two).
Document SimulateDocument(const ForwardSolution& s);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_SIMULATE_DOCUMENT_H_
