// Eigen 3.4.0's BDCSVD as ccma used it before (ccma::BdcSvd, up to commit
// 826693e), run with Eigen's assertions on and turned into a report instead
// of an abort, in every build type: the reference of the rank-decision tests
// (tests/rank_decisions_test.cc), which must tell the matrices that trip
// BDCSVD's defect (BDCSVD::perturbCol0 reading its deflation permutation at
// index -1) from those where its result is the old, valid one.
//
// The interface is plain C++ (no Eigen type): the implementation compiles its
// own copy of Eigen in a renamed namespace (eigen_bdcsvd_probe.cc), so its
// asserting instantiations cannot be mixed with the library's by the linker.
#ifndef CCMA_TESTS_EIGEN_BDCSVD_PROBE_H_
#define CCMA_TESTS_EIGEN_BDCSVD_PROBE_H_

#include <string>
#include <vector>

namespace ccma::testing {

struct BdcsvdProbe {
  bool assertion_failed = false;
  std::string assertion;                // the failed condition, as Eigen states it
  std::vector<double> singular_values;  // decreasing; empty when an assertion failed
  std::vector<double> V;                // cols x cols, column-major (compute_v), else empty
};

// BDCSVD of the rows x cols column-major matrix `A` (values, and V in full
// when compute_v), as Eigen::BDCSVD<MatrixXd>(A, compute_v ? ComputeFullV : 0).
BdcsvdProbe ProbeBdcsvd(const std::vector<double>& A, int rows, int cols, bool compute_v);

}  // namespace ccma::testing

#endif  // CCMA_TESTS_EIGEN_BDCSVD_PROBE_H_
