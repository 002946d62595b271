// The end-effector part of the control objective, e = X_EE(s) - X*, over the
// model's controlled components, and de/ds.
//
// Position components: p_WE - p*. Orientation: when roll, pitch and yaw are
// all controlled, the rotation vector Log(R_EE R*^T) (valid at any
// orientation); otherwise the listed [roll, pitch, yaw] differences, wrapped
// to (-pi, pi] (their Jacobian is singular only at pitch = +-90 degrees).
#ifndef CCMA_PROBLEMS_INTERNAL_END_EFFECTOR_ERROR_H_
#define CCMA_PROBLEMS_INTERNAL_END_EFFECTOR_ERROR_H_

#include <vector>

#include <Eigen/Core>

#include "ccma/end_effector.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

class EndEffectorError {
 public:
  explicit EndEffectorError(const Model& model);
  int size() const { return size_; }
  // e (size()) and, if not null, de/ds (size() x state_size).
  void Evaluate(const State& s, const PoseTarget& target, Eigen::VectorXd* e,
                Eigen::MatrixXd* de_ds) const;

 private:
  const Model& model_;
  std::vector<int> position_;  // controlled position components (0-2)
  std::vector<int> angles_;    // controlled rpy components (0-2), subset mode
  bool full_rotation_ = false;
  int size_ = 0;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_END_EFFECTOR_ERROR_H_
