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

// The same for the text of a waypoint file already in memory (at most
// kMaxWaypointFileBytes); `source` names it in messages ("source:line: what").
std::vector<Waypoint> ParseWaypoints(const std::string& text, const std::string& source);

}  // namespace ccma

#endif  // CCMA_WAYPOINTS_H_
