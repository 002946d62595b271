// Printing a command's document and reading one back (`simulate --from`):
// the CLI's side of the JSON. The document's values are the document layer's
// (documents/json_values.h), named here for the commands.
#ifndef CCMA_APPS_JSON_OUTPUT_H_
#define CCMA_APPS_JSON_OUTPUT_H_

#include <string>

#include <nlohmann/json.hpp>

#include "ccma/ccma.h"
#include "documents/document.h"
#include "documents/json_values.h"

namespace ccma::cli {

using documents::AddCompensationJson;
using documents::AddComplianceJson;
using documents::AddLoadedJson;
using documents::BodiesToJson;
using documents::ClearanceToJson;
using documents::JointsToJson;
using documents::LimitsViolatedToJson;
using documents::SecondaryJson;
using documents::ToJson;

// Adds ClearanceToJson as out["clearance"] when not null, and when it is
// below the margin says so on stderr in one line ("ccma COMMAND: warning: ...").
void AddClearance(const Model& model, const State& s, const std::string& command, nlohmann::json* out);

// The state in `document["bodies"]` (as BodiesToJson writes it; quaternion
// preferred, else rpy), every body of the model by name. Throws UsageError
// naming `source` and the offending key.
State StateFromJson(const Model& model, const nlohmann::json& document, const std::string& source);

// Prints one JSON document on stdout.
void PrintJson(const nlohmann::json& document);
// A document's warnings on stderr, one line each ("ccma COMMAND: warning:
// ..."), then its notes ("ccma COMMAND: note: ...").
void PrintWarnings(const documents::Document& document, const std::string& command);
// A command's document (documents/document.h): its warnings on stderr
// (PrintWarnings), then its JSON on stdout.
void PrintDocument(const documents::Document& document, const std::string& command);

}  // namespace ccma::cli

#endif  // CCMA_APPS_JSON_OUTPUT_H_
