#include "problems/internal/singularity.h"

#include "ccma/internal/dense_factorizations.h"

namespace ccma {

SmallestSingularValueResult SmallestSingularValueOfdXdu(const ConstraintSet& constraints, const EndEffectorError& error,
                                                        const PoseTarget& target, const State& s,
                                                        const Eigen::VectorXd& u, const std::vector<int>& effective,
                                                        bool with_gradient, double h, HessianSolver* solver,
                                                        EnergyDerivatives* workspace) {
  SmallestSingularValueResult out;
  const int k = static_cast<int>(effective.size());
  const int ne = error.size();
  if (k == 0 || ne == 0) return out;
  Eigen::MatrixXd S;
  {
    const Sensitivity sensitivity(constraints, s, u, effective, solver, workspace);
    // A singular flag alone (a leg free to spin about itself) leaves de/du
    // well defined; only a failed factorisation does not.
    if (!solver->factorized()) return out;
    S = sensitivity.StateSensitivity();
  }
  Eigen::VectorXd e;
  Eigen::MatrixXd de_ds;
  error.Evaluate(s, target, &e, &de_ds);
  const Eigen::MatrixXd A = de_ds * S;
  const JacobiSvd svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& values = svd.singularValues();  // decreasing
  const int last = static_cast<int>(values.size()) - 1;
  out.sigma = values[last];
  out.gap = last > 0 ? values[last - 1] - values[last] : values[last];
  out.valid = true;
  if (!with_gradient) return out;
  const Eigen::VectorXd v = svd.matrixU().col(last);
  const Eigen::VectorXd w = svd.matrixV().col(last);
  // v^T A(s', u') w at a point of the tangent line (one factorisation, one solve).
  auto vAw = [&](int l, double t, bool* ok) {
    State s_t = s;
    s_t.Plus(t * S.col(l));
    Eigen::VectorXd u_t = u;
    u_t[effective[static_cast<size_t>(l)]] += t;
    const Sensitivity sensitivity(constraints, s_t, u_t, effective, solver, workspace);
    if (!solver->factorized()) *ok = false;
    Eigen::MatrixXd F;
    error.Evaluate(s_t, target, &e, &F);
    return v.dot(F * sensitivity.StateChange(w));
  };
  out.gradient.resize(k);
  for (int l = 0; l < k; ++l) {
    bool ok = true;
    // Richardson: (4 D(h/2) - D(h)) / 3 cancels the h^2 term.
    const double coarse = (vAw(l, h, &ok) - vAw(l, -h, &ok)) / (2 * h);
    const double fine = (vAw(l, h / 2, &ok) - vAw(l, -h / 2, &ok)) / h;
    out.gradient[l] = (4 * fine - coarse) / 3;
    if (!ok) out.valid = false;
  }
  return out;
}

}  // namespace ccma
