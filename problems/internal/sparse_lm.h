// The forward problem's own Levenberg-Marquardt loop: the same analytic cost
// functions and pose increments as the Ceres path (ConstraintSet,
// PoseManifold), without Ceres' per-call preprocessing.
//
// J^T J is handled as a matrix of dense 6 x 6 blocks, one block row and
// column per body (a constraint couples at most two bodies), factorised by a
// block Cholesky factorisation of ccma's own:
//  - per model, once: a fill-reducing elimination order of the bodies (AMD
//    on the body graph), the block pattern of the factor with its fill, the
//    list of block updates of the factorisation, and where every
//    constraint's J_p^T J_q lands (no search in a sparse structure later);
//  - per iteration: J^T J accumulated block by block with fixed-size
//    products (the row count of a constraint is a template argument), one
//    numeric block LL^T (6 x 6 dense blocks: fixed-size, unrolled and
//    vectorised), one block forward / back substitution.
// On the paper's models this is 3-4 times faster per iteration than the
// previous scalar path (Eigen::SimplicialLDLT over a scalar sparse pattern
// filled through a table of entry indices), see Solve() for the
// iteration strategy and benchmarks/forward_benchmark.cc for measurements.
#ifndef CCMA_PROBLEMS_INTERNAL_SPARSE_LM_H_
#define CCMA_PROBLEMS_INTERNAL_SPARSE_LM_H_

#include <vector>

#include <Eigen/Core>

#include "ccma/internal/constraint_set.h"
#include "ccma/state.h"
#include "problems/internal/block_elimination.h"

namespace ccma {

struct SparseLmSummary {
  // Trial steps: Levenberg-Marquardt steps (one factorisation each, accepted
  // or rejected) plus the final chord steps (see chord_steps).
  int iterations = 0;
  // Of those, chord steps: the last factorisation reused with the gradient
  // at the new point (a back substitution and one evaluation, no new
  // factorisation) once the iteration is that close to convergence.
  int chord_steps = 0;
  double energy = 0;          // E at the end [m^2]
  double gradient_norm = 0;   // max |dE/ds| at the end
  // gradient_norm is an upper bound, not the value: a rigid image of an
  // assembled state, accepted on its residuals alone (Solve's converged_energy).
  bool gradient_norm_is_bound = false;
  bool converged = false;     // a convergence test held (not the iteration limit)
  // Stopped early (converged false) because Gauss-Newton converges only
  // linearly here: E > 0 at a stationary point (over-constrained or
  // unreachable controls), where each step shrinks the error by a constant
  // factor. Newton steps on the exact Hessian of E (the caller's polish)
  // converge quadratically from here.
  bool linear = false;
};

class SparseLevenbergMarquardt {
 public:
  explicit SparseLevenbergMarquardt(const ConstraintSet& constraints);

  // Minimises E(s, u) over s from `s` (updated in place), at most
  // `max_iterations` trial steps. Converges to rounding level: stops when
  // the next step would move the state by less than kStepTolerance (1e-14,
  // m or rad), when E is at rounding level (E <= 1e-31), or when E no longer
  // decreases relatively by more than 1e-15 (a stationary point with E > 0).
  // With `stop_when_linear`, stops as soon as the convergence turns linear
  // at E > 0 (see SparseLmSummary::linear). `converged_energy` [m^2]: the
  // caller knows that `s` is an exact image of a converged state (a rigid
  // motion of it, planar_rigid_motion.h) whose E, plus rounding, was this;
  // at or below it the start counts as converged (no iteration). When that
  // bound is at most 1e-24 (an assembled state) the check reads residuals
  // only (no Jacobian) and reports gradient_norm as a bound (see
  // SparseLmSummary::gradient_norm_is_bound).
  SparseLmSummary Solve(State* s, const Eigen::VectorXd& u, int max_iterations, bool stop_when_linear = false,
                        double converged_energy = 0);

 private:
  using Block = Eigen::Matrix<double, kPoseTangentSize, kPoseTangentSize>;
  using BlockVector = Eigen::Matrix<double, kPoseTangentSize, 1>;

  // One constraint block's place in the normal equations.
  struct Term {
    int block = 0;                 // index in constraints.blocks()
    int num_params = 0;            // its parameter blocks (poses, then control)
    int pos[2] = {-1, -1};         // elimination position of each pose parameter, -1: the ground
    int off = -1;                  // block of J^T J coupling the two bodies, -1 if none
    bool off_transposed = false;   // off holds J_1^T J_0 (body 1 eliminated later) rather than J_0^T J_1
    int jacobian = 0;              // offset of its Jacobians in jacobians_ (rows x 7 per pose)
  };
  // The rigid-image check of Solve: E(s, u) from the residuals alone; if it
  // is at most converged_energy, fills `summary` (converged, 0 iterations,
  // gradient_norm the bound 2 |J|_F sqrt(2 E)) and returns true.
  bool RigidImageConverged(const State& s, const Eigen::VectorXd& u, double converged_energy,
                           SparseLmSummary* summary);
  // Solve's tail of an accepted step: convergence tests, linear-rate stop,
  // chord step (see sparse_lm.cc); true when the loop ends.
  bool AfterAcceptedStep(State* s, const Eigen::VectorXd& u, double step, double decrease, int max_iterations,
                         bool stop_when_linear, double* energy, double* last_ratio, SparseLmSummary* summary);
  // C and the tangent Jacobians at (s, u) into C_ and jacobians_; returns E.
  double Evaluate(const State& s, const Eigen::VectorXd& u);
  // g_ = J^T C (elimination order) from C_ and jacobians_.
  void Gradient();
  // normal_ = J^T J from jacobians_.
  void AccumulateNormal();
  // factor_ = block LL^T of normal_ + mu diag(normal_) (clamped); false if
  // not positive definite.
  bool Factorize(double mu);
  // x = -factor^{-1} rhs (elimination order; x may not alias rhs).
  void SolveNegative(const Eigen::VectorXd& rhs, Eigen::VectorXd* x) const;
  // out = s (+) ds, ds in elimination order.
  void Plus(const State& s, const Eigen::VectorXd& ds, State* out) const;

  const ConstraintSet& constraints_;
  int bodies_ = 0;
  std::vector<int> position_;      // body -> elimination position
  std::vector<Term> terms_;
  // The block pattern of the factor (fill included) and its updates.
  BlockElimination elimination_;
  // Blocks of J^T J and of its factor, in elimination_'s layout (the fill
  // zero in normal_).
  std::vector<Block> normal_, factor_;
  Eigen::VectorXd C_, g_, ds_, chord_;
  std::vector<double> jacobians_;
  BodyFrames frames_;               // workspace: the bodies' frames at the evaluated state
  bool evaluated_ = false;          // jacobians_ holds a Jacobian
  double jacobian_frobenius_ = -1;  // |jacobians_|_F, -1: not yet computed
  State trial_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_SPARSE_LM_H_
