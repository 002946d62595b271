#include "benchmarks/simbody/base_track_motion.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "ccma/model.h"
#include "ccma/rotation.h"

namespace ccma::simbody_benchmark {

BaseTrackMotion::BaseTrackMotion(std::shared_ptr<const std::vector<Eigen::VectorXd>> controls, int base)
    : controls_(std::move(controls)), base_(base) {
  if (!controls_ || controls_->empty()) throw std::invalid_argument("BaseTrackMotion: empty track");
}

void BaseTrackMotion::Segment(double t, Eigen::Vector3d* q0, Eigen::Vector3d* dq, double* fraction) const {
  const int last = static_cast<int>(controls_->size()) - 1;
  const double clamped = std::clamp(t, 0.0, static_cast<double>(last));
  const int k = static_cast<int>(std::floor(clamped));  // k == last at the track's end
  auto planar_q = [&](int i) {
    const Eigen::Vector3d u = (*controls_)[i].segment<3>(3 * base_);
    return Eigen::Vector3d(u.z(), u.x(), u.y());  // Planar's order: theta, x, y
  };
  *q0 = planar_q(k);
  *dq = k < last ? Eigen::Vector3d(planar_q(k + 1) - *q0) : Eigen::Vector3d::Zero();
  (*dq)[0] = WrapAngle((*dq)[0]);  // the short way round
  *fraction = clamped - k;
}

void BaseTrackMotion::calcPrescribedPosition(const SimTK::State& s, int nq, SimTK::Real* q) const {
  Eigen::Vector3d q0, dq;
  double fraction;
  Segment(s.getTime(), &q0, &dq, &fraction);
  // At integer times fraction is exactly 0: q is exactly controls[k] there.
  for (int i = 0; i < nq && i < 3; ++i) q[i] = fraction == 0 ? q0[i] : q0[i] + fraction * dq[i];
}

void BaseTrackMotion::calcPrescribedPositionDot(const SimTK::State& s, int nq, SimTK::Real* qdot) const {
  Eigen::Vector3d q0, dq;
  double fraction;
  Segment(s.getTime(), &q0, &dq, &fraction);
  for (int i = 0; i < nq && i < 3; ++i) qdot[i] = dq[i];
}

void BaseTrackMotion::calcPrescribedPositionDotDot(const SimTK::State&, int nq, SimTK::Real* qdotdot) const {
  for (int i = 0; i < nq; ++i) qdotdot[i] = 0;  // piecewise linear
}

}  // namespace ccma::simbody_benchmark
