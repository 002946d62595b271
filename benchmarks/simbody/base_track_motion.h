// Prescribed motion of one mobile base in Simbody: the base's Planar
// mobilizer (q = theta [rad] about the ground's z, then x, y [m] along the
// ground's axes) follows the base's controls along a track, as a function of
// time. Time is the step index: t = k gives exactly controls[k]; in between
// the controls are interpolated linearly (headings the short way).
//
// Why a Motion and not locked q's: both Simbody solvers under test treat a
// prescribed mobilizer as given, and setting the time is their documented way
// to move it between frames (System::prescribeQ() before projectQ(), and
// Assembler::track(frameTime), which re-prescribes by itself). So each step
// changes only the time, never the state's structure, and nothing is rebuilt.
#ifndef CCMA_BENCHMARKS_SIMBODY_BASE_TRACK_MOTION_H_
#define CCMA_BENCHMARKS_SIMBODY_BASE_TRACK_MOTION_H_

#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Simbody.h>

namespace ccma::simbody_benchmark {

class BaseTrackMotion : public SimTK::Motion::Custom::Implementation {
 public:
  // controls: u per step (3 per base: x [m], y [m], theta [rad]; model.h);
  // base: which base's three entries this motion prescribes.
  BaseTrackMotion(std::shared_ptr<const std::vector<Eigen::VectorXd>> controls, int base);

  Implementation* clone() const override { return new BaseTrackMotion(*this); }
  SimTK::Motion::Level getLevel(const SimTK::State&) const override { return SimTK::Motion::Position; }

  // q = (theta, x, y) at the state's time.
  void calcPrescribedPosition(const SimTK::State& s, int nq, SimTK::Real* q) const override;
  // dq/dt of the interpolation (per unit of time = per step). Never used by
  // position-level projection or assembly, but Simbody requires it.
  void calcPrescribedPositionDot(const SimTK::State& s, int nq, SimTK::Real* qdot) const override;
  void calcPrescribedPositionDotDot(const SimTK::State& s, int nq, SimTK::Real* qdotdot) const override;

 private:
  // The segment [k, k+1] holding time t (clamped to the track): q at its
  // start (theta, x, y), the change over it, and the fraction of it covered.
  void Segment(double t, Eigen::Vector3d* q0, Eigen::Vector3d* dq, double* fraction) const;

  std::shared_ptr<const std::vector<Eigen::VectorXd>> controls_;
  int base_;
};

}  // namespace ccma::simbody_benchmark

#endif  // CCMA_BENCHMARKS_SIMBODY_BASE_TRACK_MOTION_H_
