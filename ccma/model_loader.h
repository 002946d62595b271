// Loading and validating CCMA model files (contract: shared/model_format.md).
//
// Every rejection is a ModelError whose message names the file, the line
// (where YAML gives one) and the offending key or name, e.g.
//   models/bad.yaml:14: joints[2].axis: must not be the zero vector
// Nothing here aborts or prints; callers decide how to report.
#ifndef CCMA_MODEL_LOADER_H_
#define CCMA_MODEL_LOADER_H_

#include <stdexcept>
#include <string>
#include <vector>

#include "ccma/model.h"

namespace ccma {

// A malformed or unreadable model file.
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads and validates the model file at `path` (YAML, or JSON).
// Unknown keys are not errors (the format may be extended); each one adds a
// line to `warnings` when it is given. Throws ModelError on any problem.
Model LoadModel(const std::string& path,
                std::vector<std::string>* warnings = nullptr);

// The same for a model held in memory; `source_name` stands in for the file
// name in messages.
Model LoadModelFromString(const std::string& text,
                          const std::string& source_name,
                          std::vector<std::string>* warnings = nullptr);

}  // namespace ccma

#endif  // CCMA_MODEL_LOADER_H_
