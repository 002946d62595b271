#include "apps/json_output.h"

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

void PrintJson(const nlohmann::json& document) { std::cout << document.dump(1) << std::endl; }

}  // namespace ccma::cli
