// All constraints C(s, u) of a model: one analytic cost function per joint
// and two per mobile base (planar, motor), built once from the Model.
//
// Row layout of C: the blocks in `blocks()` order (joints in file order, then
// per base its planar and motor rows); block b starts at blocks()[b].row.
// The cost functions are owned here and shared with Ceres problems.
#ifndef CCMA_CONSTRAINT_SET_H_
#define CCMA_CONSTRAINT_SET_H_

#include <memory>
#include <string>
#include <vector>

#include <ceres/cost_function.h>
#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

struct ConstraintBlock {
  std::unique_ptr<ceres::CostFunction> cost;
  std::vector<int> bodies;  // pose blocks it reads, in parameter order
  int base = -1;            // >= 0: it also reads that base's control block
  int row = 0;              // first row in C
  int rows = 0;
  std::string label;        // e.g. "joints[3] (revolute base0-post0)"
};

class ConstraintSet {
 public:
  explicit ConstraintSet(const Model& model);

  const std::vector<ConstraintBlock>& blocks() const { return blocks_; }
  int num_rows() const { return num_rows_; }
  int state_size() const { return state_size_; }
  int num_controls() const { return num_controls_; }

  // C(s, u) into `C` (size num_rows()); and, where not null, the dense
  // Jacobians J_s = dC/ds (num_rows x 6 n_bodies, tangent, see state.h) and
  // J_u = dC/du (num_rows x 3 n_bases). u: 3 per base [m, m, rad].
  void Evaluate(const State& s, const Eigen::VectorXd& u, Eigen::VectorXd* C,
                Eigen::MatrixXd* J_s = nullptr, Eigen::MatrixXd* J_u = nullptr) const;

  // E(s, u) = 1/2 C^T C.
  double Energy(const State& s, const Eigen::VectorXd& u) const;

 private:
  std::vector<ConstraintBlock> blocks_;
  int num_rows_ = 0;
  int state_size_ = 0;
  int num_controls_ = 0;
};

}  // namespace ccma

#endif  // CCMA_CONSTRAINT_SET_H_
