// Parsing untrusted YAML text into a document, shared by the model loader and
// the closure-file reader: a guard against deeply nested flow collections,
// then yaml-cpp, every failure a ModelError "source:line: not valid YAML: ...".
#ifndef CCMA_FORMATS_INTERNAL_YAML_DOCUMENT_H_
#define CCMA_FORMATS_INTERNAL_YAML_DOCUMENT_H_

#include <string>

#include <yaml-cpp/yaml.h>

namespace ccma {
namespace internal {

// The YAML document in `text`; `source` names it in messages. A file holds
// one document: a second one (after `---` or `...`) is a ModelError
// naming its line, and so is a later document that is not valid YAML.
YAML::Node ParseYamlText(const std::string& text, const std::string& source);

// "source:line" (1-based) when the mark has a line, else "source".
std::string WithLine(const std::string& source, const YAML::Mark& mark);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_YAML_DOCUMENT_H_
