// Eigen in its own namespace, with every eigen_assert a C++ exception: see
// eigen_bdcsvd_probe.h. This file includes no other header that includes
// Eigen (its include guards would keep the renamed copy out) and is compiled
// on its own, outside the unity batches (tests/CMakeLists.txt).
#include "tests/eigen_bdcsvd_probe.h"

#include <stdexcept>

namespace ccma::testing {
namespace {

struct EigenAssertion : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace
}  // namespace ccma::testing

#define Eigen ccma_bdcsvd_probe_eigen
#define eigen_assert(condition) \
  ((condition) ? static_cast<void>(0) : throw ::ccma::testing::EigenAssertion(#condition))
#include <Eigen/SVD>

namespace ccma::testing {

BdcsvdProbe ProbeBdcsvd(const std::vector<double>& A, int rows, int cols, bool compute_v) {
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic>;
  if (static_cast<long>(A.size()) != static_cast<long>(rows) * cols) {
    throw std::invalid_argument("ProbeBdcsvd: A has " + std::to_string(A.size()) + " entries, not rows x cols");
  }
  const Matrix M = Eigen::Map<const Matrix>(A.data(), rows, cols);
  BdcsvdProbe out;
  try {
    const Eigen::BDCSVD<Matrix> svd(M, compute_v ? static_cast<unsigned>(Eigen::ComputeFullV) : 0u);
    out.singular_values.assign(svd.singularValues().data(), svd.singularValues().data() + svd.singularValues().size());
    if (compute_v) out.V.assign(svd.matrixV().data(), svd.matrixV().data() + svd.matrixV().size());
  } catch (const EigenAssertion& e) {
    out.assertion_failed = true;
    out.assertion = e.what();
  }
  return out;
}

}  // namespace ccma::testing
