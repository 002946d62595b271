#include "problems/internal/finite_differences.h"

namespace ccma {

Eigen::MatrixXd CentralDifferenceJacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                                          const Eigen::VectorXd& x, double h) {
  Eigen::MatrixXd J;
  for (int c = 0; c < x.size(); ++c) {
    Eigen::VectorXd plus = x, minus = x;
    plus[c] += h;
    minus[c] -= h;
    const Eigen::VectorXd f_plus = f(plus);
    const Eigen::VectorXd f_minus = f(minus);
    if (c == 0) J.resize(f_plus.size(), x.size());
    J.col(c) = (f_plus - f_minus) / (2 * h);
  }
  return J;
}

Eigen::VectorXd CentralDifferenceGradient(const std::function<double(const Eigen::VectorXd&)>& f,
                                          const Eigen::VectorXd& x, double h) {
  Eigen::VectorXd g(x.size());
  for (int c = 0; c < x.size(); ++c) {
    Eigen::VectorXd plus = x, minus = x;
    plus[c] += h;
    minus[c] -= h;
    g[c] = (f(plus) - f(minus)) / (2 * h);
  }
  return g;
}

}  // namespace ccma
