// JSON shapes shared by the `ccma` sub-commands (cli.md).
#ifndef CCMA_APPS_JSON_OUTPUT_H_
#define CCMA_APPS_JSON_OUTPUT_H_

#include <nlohmann/json.hpp>

#include "ccma/ccma.h"

namespace ccma::cli {

nlohmann::json ToJson(const Eigen::VectorXd& v);
// {"position": [..], "rotation": [[..],[..],[..]], "rpy": [..]}
nlohmann::json ToJson(const EndEffectorPose& pose);
// [{"name", "position", "rpy"}] for every body (rpy of R_WB, world axes).
nlohmann::json BodiesToJson(const Model& model, const State& s);

// Prints one JSON document on stdout.
void PrintJson(const nlohmann::json& document);

}  // namespace ccma::cli

#endif  // CCMA_APPS_JSON_OUTPUT_H_
