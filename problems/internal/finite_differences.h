// Central finite differences of re-solved forward problems: the baseline the
// paper's implicit-function gradients avoid (2k forward solves per Jacobian
// over k controls), kept for benchmarks and tests.
#ifndef CCMA_PROBLEMS_INTERNAL_FINITE_DIFFERENCES_H_
#define CCMA_PROBLEMS_INTERNAL_FINITE_DIFFERENCES_H_

#include <functional>

#include <Eigen/Core>

namespace ccma {

// d f / d x at x by central differences with step h: column c is
// (f(x + h e_c) - f(x - h e_c)) / 2h. f must return vectors of one size.
Eigen::MatrixXd CentralDifferenceJacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                                          const Eigen::VectorXd& x, double h);

// d f / d x for a scalar f (the gradient, as a vector).
Eigen::VectorXd CentralDifferenceGradient(const std::function<double(const Eigen::VectorXd&)>& f,
                                          const Eigen::VectorXd& x, double h);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_FINITE_DIFFERENCES_H_
