// The model and the document of `ccma generate` (docs/cli.md) and of
// Python's generate(): a generated model file (formats/model_generator.h),
// validated by loading it, and its counts.
#ifndef CCMA_DOCUMENTS_GENERATE_DOCUMENT_H_
#define CCMA_DOCUMENTS_GENERATE_DOCUMENT_H_

#include <string>

#include "ccma/model.h"
#include "documents/document.h"

namespace ccma::documents {

// What to generate, as the command's flags say it.
struct GenerateSettings {
  std::string kind = "ccma";  // ccma | stewart_gough | legged
  int agents = 0;             // mobile bases, legs (stewart_gough) or quadrupeds, [3, 1000]
  // Why the settings cannot be generated, in the flags' words ("--agents
  // must be ..."); false then.
  bool IsValid(std::string* why) const;
};

struct Generated {
  std::string text;   // the model file (YAML)
  Model model;        // the text, loaded (so validated)
  Document document;  // {model, agents, actuated_joints, bodies, state_size, controls}, without "out"
};

// The model of `settings` (valid: IsValid), named `source` in messages.
// Throws std::invalid_argument for invalid settings.
Generated GenerateModel(const GenerateSettings& settings, const std::string& source);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_GENERATE_DOCUMENT_H_
