// A generic Jacobian checker for ccma cost functions: compares the analytic
// Jacobian with central differences, Richardson-extrapolated (error O(h^4)),
// taken in the tangent space of each pose block (state.h) and in the plain
// coordinates of other blocks (controls).
#ifndef CCMA_TESTS_DERIVATIVE_CHECKER_H_
#define CCMA_TESTS_DERIVATIVE_CHECKER_H_

#include <algorithm>
#include <cmath>
#include <vector>

#include <ceres/cost_function.h>
#include <Eigen/Core>

#include "ccma/internal/pose_manifold.h"

namespace ccma::testing {

struct ParameterBlock {
  std::vector<double> values;
  bool is_pose = false;  // 7 doubles with PoseManifold, or plain
  int tangent_size() const { return is_pose ? 6 : static_cast<int>(values.size()); }
};

struct JacobianComparison {
  double max_abs_error = 0;     // max |analytic - numeric| over all entries
  double max_abs_entry = 0;     // max |numeric| (scale)
  bool lifted_column_nonzero = false;  // a pose block's 7th column was not 0
};

// Residuals at `blocks` with the tangent increment `delta` applied to block b.
inline Eigen::VectorXd EvaluateAt(const ceres::CostFunction& cost,
                                  std::vector<ParameterBlock> blocks, int b,
                                  const Eigen::VectorXd& delta) {
  if (blocks[b].is_pose) {
    std::vector<double> moved(7);
    PoseManifold().Plus(blocks[b].values.data(), delta.data(), moved.data());
    blocks[b].values = moved;
  } else {
    for (int i = 0; i < delta.size(); ++i) blocks[b].values[i] += delta[i];
  }
  std::vector<const double*> params;
  for (const auto& block : blocks) params.push_back(block.values.data());
  Eigen::VectorXd r(cost.num_residuals());
  cost.Evaluate(params.data(), r.data(), nullptr);
  return r;
}

inline JacobianComparison CompareJacobians(const ceres::CostFunction& cost,
                                           const std::vector<ParameterBlock>& blocks,
                                           double step = 1e-3) {
  const int rows = cost.num_residuals();
  JacobianComparison out;
  // Analytic Jacobians.
  std::vector<std::vector<double>> storage;
  std::vector<double*> jacobians;
  std::vector<const double*> params;
  for (const auto& block : blocks) {
    storage.emplace_back(rows * block.values.size(), 1e300);  // catch unwritten entries
    params.push_back(block.values.data());
  }
  for (auto& s : storage) jacobians.push_back(s.data());
  Eigen::VectorXd r(rows);
  cost.Evaluate(params.data(), r.data(), jacobians.data());

  for (size_t b = 0; b < blocks.size(); ++b) {
    const int cols = static_cast<int>(blocks[b].values.size());
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
        J(storage[b].data(), rows, cols);
    if (blocks[b].is_pose && J.col(6).cwiseAbs().maxCoeff() != 0.0) {
      out.lifted_column_nonzero = true;
    }
    const int n = blocks[b].tangent_size();
    for (int k = 0; k < n; ++k) {
      auto central = [&](double h) {
        Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
        d[k] = h;
        const Eigen::VectorXd plus = EvaluateAt(cost, blocks, static_cast<int>(b), d);
        const Eigen::VectorXd minus = EvaluateAt(cost, blocks, static_cast<int>(b), -d);
        return Eigen::VectorXd((plus - minus) / (2 * h));
      };
      const Eigen::VectorXd numeric = (4.0 * central(step / 2) - central(step)) / 3.0;
      out.max_abs_entry = std::max(out.max_abs_entry, numeric.cwiseAbs().maxCoeff());
      out.max_abs_error = std::max(out.max_abs_error, (J.col(k) - numeric).cwiseAbs().maxCoeff());
    }
  }
  return out;
}

// f(delta) = w . r(x (+) delta), delta stacked over the pose blocks (6 each);
// plain blocks move by `plain_delta` (or stay) .
inline double WeightedResidual(const ceres::CostFunction& cost, std::vector<ParameterBlock> blocks,
                               const Eigen::VectorXd& w, const Eigen::VectorXd& pose_delta,
                               const Eigen::VectorXd& plain_delta = Eigen::VectorXd()) {
  int offset = 0, plain_offset = 0;
  for (auto& block : blocks) {
    if (block.is_pose) {
      std::vector<double> moved(7);
      PoseManifold().Plus(block.values.data(), pose_delta.data() + offset, moved.data());
      block.values = moved;
      offset += 6;
    } else if (plain_delta.size() > 0) {
      for (double& v : block.values) v += plain_delta[plain_offset++];
    }
  }
  std::vector<const double*> params;
  for (const auto& block : blocks) params.push_back(block.values.data());
  Eigen::VectorXd r(cost.num_residuals());
  cost.Evaluate(params.data(), r.data(), nullptr);
  return w.dot(r);
}

// Numeric Hessian of f over the pose tangents: central second differences,
// Richardson-extrapolated (error O(h^4)).
inline Eigen::MatrixXd NumericWeightedHessian(const ceres::CostFunction& cost,
                                              const std::vector<ParameterBlock>& blocks,
                                              const Eigen::VectorXd& w, double step = 1e-3) {
  int n = 0;
  for (const auto& block : blocks) n += block.is_pose ? 6 : 0;
  auto second = [&](int i, int j, double h) {
    auto f = [&](double si, double sj) {
      Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
      d[i] += si * h;
      d[j] += sj * h;
      return WeightedResidual(cost, blocks, w, d);
    };
    return (f(1, 1) - f(1, -1) - f(-1, 1) + f(-1, -1)) / (4 * h * h);
  };
  Eigen::MatrixXd H(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j <= i; ++j) {
      H(i, j) = H(j, i) = (4.0 * second(i, j, step / 2) - second(i, j, step)) / 3.0;
    }
  }
  return H;
}

}  // namespace ccma::testing

#endif  // CCMA_TESTS_DERIVATIVE_CHECKER_H_
