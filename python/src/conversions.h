// Conversions shared by the binding files: options from keyword arguments,
// waypoints from an (N x 7) array and the check of their values.
#ifndef CCMA_PYTHON_SRC_CONVERSIONS_H_
#define CCMA_PYTHON_SRC_CONVERSIONS_H_

#include <optional>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "ccma/loads.h"
#include "formats/waypoints.h"

namespace ccma::python {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// `defaults` with every keyword set as an attribute of the bound options
// class (so each goes through its property's checks); an unknown keyword is
// a TypeError, as for any Python function.
template <typename Options>
Options WithKeywords(const Options& defaults, const pybind11::kwargs& kwargs) {
  pybind11::object self = pybind11::cast(defaults);
  for (auto item : kwargs) {
    const std::string key = pybind11::str(item.first);
    if (key.empty() || key[0] == '_' || !pybind11::hasattr(self, key.c_str())) {
      throw pybind11::type_error("unexpected keyword argument '" + key + "'");
    }
    pybind11::setattr(self, item.first, item.second);
  }
  return self.cast<Options>();
}

// A `wrench=` argument [fx, fy, fz [N], mx, my, mz [N*m]] as the CLI's
// --wrench checks it; none: no wrench. `what` names the call in the message.
inline ExternalWrench WrenchFrom(const std::optional<Eigen::VectorXd>& wrench, const std::string& what) {
  ExternalWrench w;
  if (!wrench) return w;
  if (wrench->size() != 6 || !wrench->allFinite() || wrench->cwiseAbs().maxCoeff() > 1e6) {
    throw pybind11::value_error(what + ": wrench must be 6 finite numbers fx,fy,fz [N], mx,my,mz [N*m], each in [-1e6, 1e6]");
  }
  w.force = wrench->head<3>();
  w.moment = wrench->tail<3>();
  return w;
}

// Rows [time, x, y, z, roll, pitch, yaw] ([s], [m], [rad]) -> waypoints.
inline std::vector<Waypoint> WaypointsFromArray(const Eigen::Ref<const RowMatrix>& a) {
  if (a.cols() != 7) {
    throw pybind11::value_error("waypoints: expected N x 7 rows [time, x, y, z, roll, pitch, yaw], got " +
                                std::to_string(a.cols()) + " columns");
  }
  if (a.rows() > kMaxWaypoints) {  // before allocating them
    throw pybind11::value_error("waypoints: " + std::to_string(a.rows()) + " rows; at most " +
                                std::to_string(kMaxWaypoints) + " are allowed");
  }
  std::vector<Waypoint> w(a.rows());
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    w[i].time = a(i, 0);
    w[i].position = a.row(i).segment<3>(1).transpose();
    w[i].rpy = a.row(i).segment<3>(4).transpose();
  }
  return w;
}

// Waypoints given to follow, plan or replay, held to the rules of the
// waypoint CSV (formats/waypoints.h WaypointListError, docs/waypoints.md):
// at most kMaxWaypoints, every value finite and within its bound, no time
// smaller than the one before (equal times are allowed). A breach is a
// ValueError naming the waypoint's index and value.
inline void CheckWaypoints(const std::vector<Waypoint>& waypoints) {
  const std::string why = WaypointListError(waypoints);
  if (!why.empty()) throw pybind11::value_error(why);
}

}  // namespace ccma::python

#endif  // CCMA_PYTHON_SRC_CONVERSIONS_H_
