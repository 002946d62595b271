// `ccma check --model=FILE`: validate a model and analyse its mobility at home
// (the document: documents/check_document.h).
#include <iostream>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "documents/check_document.h"

namespace ccma::cli {

int RunCheck(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "check");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "check"));
  // A mechanism that is not what a user expects is said so on stderr too.
  PrintDocument(documents::CheckDocument(model), "check");
  return 0;
}

}  // namespace ccma::cli
