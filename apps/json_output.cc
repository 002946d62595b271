#include "apps/json_output.h"

#include <algorithm>
#include <iostream>

namespace ccma::cli {

nlohmann::json ToJson(const Eigen::VectorXd& v) {
  return nlohmann::json(std::vector<double>(v.data(), v.data() + v.size()));
}

nlohmann::json ToJson(const EndEffectorPose& pose) {
  nlohmann::json rotation = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) {
    rotation.push_back({pose.rotation(r, 0), pose.rotation(r, 1), pose.rotation(r, 2)});
  }
  return {{"position", ToJson(pose.position)}, {"rotation", rotation}, {"rpy", ToJson(pose.rpy)}};
}

nlohmann::json BodiesToJson(const Model& model, const State& s) {
  nlohmann::json bodies = nlohmann::json::array();
  for (int i = 0; i < model.num_bodies(); ++i) {
    bodies.push_back({{"name", model.bodies[i].name},
                      {"position", ToJson(s.p_WB(i))},
                      {"rpy", ToJson(RpyFromRotation(s.R_WB(i)))}});
  }
  return bodies;
}

namespace {

// Objects one key per line; arrays of scalars (vectors, matrix rows) inline.
void Write(const nlohmann::json& j, int indent, std::ostream& os) {
  const std::string pad(indent, ' '), inner(indent + 2, ' ');
  auto all_scalars = [](const nlohmann::json& a) {
    for (const auto& e : a) {
      if (e.is_structured() && !(e.is_array() && std::none_of(e.begin(), e.end(), [](const auto& x) {
                                   return x.is_structured();
                                 }))) {
        return false;
      }
    }
    return true;
  };
  if (j.is_object()) {
    os << "{";
    bool first = true;
    for (auto it = j.begin(); it != j.end(); ++it) {
      os << (first ? "\n" : ",\n") << inner << nlohmann::json(it.key()).dump() << ": ";
      Write(it.value(), indent + 2, os);
      first = false;
    }
    os << (first ? "}" : "\n" + pad + "}");
  } else if (j.is_array() && !all_scalars(j)) {
    os << "[";
    bool first = true;
    for (const auto& e : j) {
      os << (first ? "\n" : ",\n") << inner;
      Write(e, indent + 2, os);
      first = false;
    }
    os << (first ? "]" : "\n" + pad + "]");
  } else {
    os << j.dump();
  }
}

}  // namespace

void PrintJson(const nlohmann::json& document) {
  Write(document, 0, std::cout);
  std::cout << std::endl;
}

}  // namespace ccma::cli
