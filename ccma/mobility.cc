#include "ccma/mobility.h"

#include <Eigen/SVD>

#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"

namespace ccma {
namespace {

int Rank(const Eigen::VectorXd& singular_values, double threshold) {
  int rank = 0;
  for (int i = 0; i < singular_values.size(); ++i) rank += singular_values[i] > threshold;
  return rank;
}

}  // namespace

MobilityReport AnalyzeMobility(const Model& model, const State& s, const Eigen::VectorXd& u,
                               double rank_tolerance) {
  const ConstraintSet constraints(model);
  MobilityReport report;
  report.constraint_rows = constraints.num_rows();
  Eigen::VectorXd C;
  Eigen::MatrixXd J_s, J_u;
  constraints.Evaluate(s, u, &C, &J_s, &J_u);
  report.energy = 0.5 * C.squaredNorm();
  const int n = model.state_size();

  const Eigen::JacobiSVD<Eigen::MatrixXd> svd_s(J_s);
  const Eigen::VectorXd sigma = svd_s.singularValues();
  const double scale = std::max(1.0, sigma.size() > 0 ? sigma[0] : 0.0);
  report.constraint_rank = Rank(sigma, rank_tolerance * scale);
  report.dof_with_controls_fixed = n - report.constraint_rank;
  report.rigid_with_controls_fixed = report.dof_with_controls_fixed == 0;
  report.smallest_singular_value =
      sigma.size() >= n ? sigma[n - 1] : 0.0;  // fewer rows than columns: singular

  // Motions with the effective controls free: null space of [J_s, J_u_eff].
  const std::vector<int> effective = model.effective_control_indices();
  Eigen::MatrixXd J(J_s.rows(), n + static_cast<int>(effective.size()));
  J.leftCols(n) = J_s;
  for (size_t c = 0; c < effective.size(); ++c) J.col(n + c) = J_u.col(effective[c]);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
  const int rank = Rank(svd.singularValues(), rank_tolerance * scale);
  report.dof_with_controls_free = static_cast<int>(J.cols()) - rank;
  const Eigen::MatrixXd null_space = svd.matrixV().rightCols(report.dof_with_controls_free);

  const Eigen::MatrixXd X = EndEffectorJacobian(model, s) * null_space.topRows(n);
  if (X.cols() > 0) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd_x(X);
    report.end_effector_dof = Rank(svd_x.singularValues(), rank_tolerance);
  }
  return report;
}

}  // namespace ccma
