// A command's document: the JSON that `ccma COMMAND` prints on stdout and
// Python's result returns from to_dict() (the same object, built by the same
// function in documents/*_document.h), and the warnings the CLI says on
// stderr, one line each ("ccma COMMAND: warning: <text>"), in order.
#ifndef CCMA_DOCUMENTS_DOCUMENT_H_
#define CCMA_DOCUMENTS_DOCUMENT_H_

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace ccma::documents {

struct Document {
  nlohmann::json json;
  std::vector<std::string> warnings;
  // What is worth knowing but not a fault ("ccma COMMAND: note: <text>"),
  // said after the warnings.
  std::vector<std::string> notes;

  // The JSON's "warning" and the same line among the warnings; nothing when
  // `warning` is empty.
  void Warn(const std::string& warning) {
    if (warning.empty()) return;
    json["warning"] = warning;
    warnings.push_back(warning);
  }
};

// Appends `text` to a "; "-separated warning (as the commands join theirs).
inline void JoinWarning(const std::string& text, std::string* warning) {
  *warning += (warning->empty() ? "" : "; ") + text;
}

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_DOCUMENT_H_
