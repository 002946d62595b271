#include "ccma/waypoints.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace ccma {

std::vector<Waypoint> LoadWaypoints(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw WaypointError(path + ": is a directory");
  std::ifstream in(path);
  if (!in) throw WaypointError(path + ": cannot open the waypoint file");
  std::vector<Waypoint> waypoints;
  std::string line;
  int number = 0;
  bool header = false;
  auto fail = [&](const std::string& what) {
    throw WaypointError(path + ":" + std::to_string(number) + ": " + what);
  };
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    if (!header) {
      std::string compact;
      for (char c : line) {
        if (c != ' ' && c != '\t') compact += c;
      }
      if (compact != "time,x,y,z,roll,pitch,yaw") fail("the header must be time,x,y,z,roll,pitch,yaw");
      header = true;
      continue;
    }
    std::vector<double> values;
    std::stringstream ss(line);
    std::string item;
    while (std::getline(ss, item, ',')) {
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(item.c_str(), &end);
      while (end != nullptr && (*end == ' ' || *end == '\t')) ++end;
      if (end == item.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v)) {
        fail("'" + item + "' is not a finite number");
      }
      values.push_back(v);
    }
    if (values.size() != 7) fail("expected 7 values, got " + std::to_string(values.size()));
    Waypoint w;
    w.time = values[0];
    w.position = Eigen::Vector3d(values[1], values[2], values[3]);
    w.rpy = Eigen::Vector3d(values[4], values[5], values[6]);
    if (!waypoints.empty() && w.time < waypoints.back().time) fail("time goes backwards");
    waypoints.push_back(w);
  }
  if (!header) throw WaypointError(path + ": no header line (time,x,y,z,roll,pitch,yaw)");
  if (waypoints.empty()) throw WaypointError(path + ": no waypoints");
  return waypoints;
}

}  // namespace ccma
