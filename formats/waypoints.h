// End-effector waypoint files for `ccma trajectory` (CSV).
//
//   # comments and blank lines are ignored
//   time,x,y,z,roll,pitch,yaw          <- this header, exactly
//   0,0,0,0.6,0,0,0                     <- s, m, m, m, rad, rad, rad
//   5,0,0.1,0.6,0,0,0
// Times must not decrease. Components the model does not control are ignored.
//
// The file is untrusted: it must be a regular file of at most
// kMaxModelFileBytes with at most kMaxWaypoints rows, times in
// [-kMaxTime, kMaxTime] s and positions and angles in
// [-kMaxMagnitude, kMaxMagnitude] m or rad (ccma/limits.h).
#ifndef CCMA_WAYPOINTS_H_
#define CCMA_WAYPOINTS_H_

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ccma {

struct Waypoint {
  double time = 0;                                  // s
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // m
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();       // rad
};

// A malformed waypoint file; the message names file and line.
class WaypointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads and validates the waypoint file at `path`; throws WaypointError.
std::vector<Waypoint> LoadWaypoints(const std::string& path);

// What breaks the file's rules in `waypoints` given in memory (Python's
// follow, plan and replay take lists and arrays, not files): more than
// kMaxWaypoints of them, a value that is not finite or beyond its bound (the
// same bounds as the file's columns), or a time smaller than the one before
// (equal times are allowed). Returns "" when they keep every rule, else a
// message naming the first bad waypoint and value, e.g.
//   waypoints[2].time (0.5) is smaller than waypoints[1].time (1): time goes backwards
//   waypoints[0].y (nan) must be a finite number in [-10000, 10000] (m)
// No waypoints at all is not an error here (a path with nothing to do).
std::string WaypointListError(const std::vector<Waypoint>& waypoints);

// The same for the text of a waypoint file already in memory (at most
// kMaxWaypointFileBytes); `source` names it in messages ("source:line: what").
std::vector<Waypoint> ParseWaypoints(const std::string& text, const std::string& source);

}  // namespace ccma

#endif  // CCMA_WAYPOINTS_H_
