#include "problems/internal/pivot_ratio.h"

namespace ccma {
namespace {

// Every pivot over the largest one's magnitude (0 when all vanish).
Eigen::VectorXd PivotRatios(const HessianSolver& solver) {
  const Eigen::VectorXd d = solver.pivots();
  const double largest = d.cwiseAbs().maxCoeff();
  return largest > 0 ? Eigen::VectorXd(d / largest) : Eigen::VectorXd::Zero(d.size());
}

}  // namespace

PivotRatioResult PivotRatioOfdGds(const ConstraintSet& constraints, const State& s, const Eigen::VectorXd& u,
                                  const std::vector<int>& effective, bool with_gradient, double h,
                                  HessianSolver* solver, EnergyDerivatives* workspace) {
  PivotRatioResult out;
  const int k = static_cast<int>(effective.size());
  Eigen::MatrixXd S;
  {
    const Sensitivity sensitivity(constraints, s, u, effective, solver, workspace);
    if (!solver->factorized()) return out;
    out.rho = solver->pivot_ratio();
    out.ratios = PivotRatios(*solver);
    out.valid = true;
    if (!with_gradient) return out;
    S = sensitivity.StateSensitivity();
  }
  const Eigen::Index n = out.ratios.size();
  Eigen::Index smallest = 0;
  out.ratios.minCoeff(&smallest);
  // The ratios at a point of the tangent line: the Hessian there and one
  // factorisation (same fixed order, so the same pivots move smoothly).
  auto ratios_at = [&](int l, double t, bool* ok) {
    State s_t = s;
    s_t.Plus(t * S.col(l));
    Eigen::VectorXd u_t = u;
    u_t[effective[static_cast<size_t>(l)]] += t;
    constraints.EvaluateDerivatives(s_t, u_t, workspace);
    if (!solver->Factorize(workspace->H)) *ok = false;
    return PivotRatios(*solver);
  };
  out.ratio_gradients.resize(n, k);
  for (int l = 0; l < k; ++l) {
    bool ok = true;
    // Richardson: (4 D(h/2) - D(h)) / 3 cancels the h^2 term.
    const Eigen::VectorXd coarse = (ratios_at(l, h, &ok) - ratios_at(l, -h, &ok)) / (2 * h);
    const Eigen::VectorXd fine = (ratios_at(l, h / 2, &ok) - ratios_at(l, -h / 2, &ok)) / h;
    out.ratio_gradients.col(l) = (4 * fine - coarse) / 3;
    if (!ok) out.valid = false;
  }
  out.gradient = out.ratio_gradients.row(smallest).transpose();
  return out;
}

}  // namespace ccma
