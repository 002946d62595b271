#include "problems/internal/plan_system.h"

#include <cmath>

#include <Eigen/SparseLU>

namespace ccma {
namespace {

// a . d_k for one row.
double RowTimes(const PlanSystem& system, const PlanRow& r, const Eigen::VectorXd& d) {
  return r.row.a.dot(d.segment(static_cast<Eigen::Index>(r.step) * system.controls, system.controls));
}

// Solves the KKT system with the rows `active` as equalities. A tiny
// negative diagonal in the multipliers' block keeps it factorisable when
// rows repeat (two pairs with the same gradient).
bool SolveWithActive(const PlanSystem& system, double mu, const std::vector<int>& active, Eigen::VectorXd* d) {
  const Eigen::Index n = system.H.rows(), m = static_cast<Eigen::Index>(active.size());
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(system.H.nonZeros() + n + m * (2 * system.controls + 1)));
  for (int col = 0; col < system.H.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(system.H, col); it; ++it) {
      triplets.emplace_back(it.row(), it.col(), it.value());
    }
  }
  for (Eigen::Index i = 0; i < n; ++i) triplets.emplace_back(i, i, mu);
  Eigen::VectorXd rhs(n + m);
  rhs.head(n) = -system.g;
  for (Eigen::Index r = 0; r < m; ++r) {
    const PlanRow& row = system.rows[static_cast<size_t>(active[static_cast<size_t>(r)])];
    const Eigen::Index first = static_cast<Eigen::Index>(row.step) * system.controls;
    for (int c = 0; c < system.controls; ++c) {
      if (row.row.a[c] == 0) continue;
      triplets.emplace_back(n + r, first + c, row.row.a[c]);
      triplets.emplace_back(first + c, n + r, row.row.a[c]);
    }
    triplets.emplace_back(n + r, n + r, -1e-12);
    rhs[n + r] = row.row.b;
  }
  Eigen::SparseMatrix<double> K(n + m, n + m);
  K.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(K);
  if (lu.info() != Eigen::Success) return false;
  const Eigen::VectorXd x = lu.solve(rhs);
  if (lu.info() != Eigen::Success || !x.allFinite()) return false;
  *d = x.head(n);
  return true;
}

}  // namespace

bool SolvePlanSystem(const PlanSystem& system, double mu, double max_change, int max_passes, Eigen::VectorXd* d) {
  PlanSystem boxed = system;  // the box's rows are appended as they are needed
  std::vector<int> active;
  std::vector<bool> held(system.rows.size(), false);
  std::vector<bool> bounded(static_cast<size_t>(system.H.rows()), false);
  for (int pass = 0; pass <= max_passes; ++pass) {
    if (!SolveWithActive(boxed, mu, active, d)) return false;
    bool grew = false;
    for (Eigen::Index i = 0; i < d->size(); ++i) {
      if (bounded[static_cast<size_t>(i)] || std::abs((*d)[i]) <= max_change) continue;
      const double sign = (*d)[i] > 0 ? -1.0 : 1.0;  // -d_i >= -max or d_i >= -max
      PlanRow bound;
      bound.step = static_cast<int>(i / system.controls);
      bound.row.a = Eigen::RowVectorXd::Zero(system.controls);
      bound.row.a[i % system.controls] = sign;
      bound.row.b = -max_change;
      bounded[static_cast<size_t>(i)] = true;
      active.push_back(static_cast<int>(boxed.rows.size()));
      boxed.rows.push_back(bound);
      grew = true;
    }
    for (size_t i = 0; i < system.rows.size(); ++i) {
      const PlanRow& r = boxed.rows[i];
      if (held[i] || RowTimes(system, r, *d) >= r.row.b - 1e-12 * (1.0 + std::abs(r.row.b))) continue;
      held[i] = true;
      active.push_back(static_cast<int>(i));
      grew = true;
    }
    if (!grew) return true;
    held.resize(boxed.rows.size(), true);
  }
  return false;
}

}  // namespace ccma
