// LoadModel and LoadModelFromString: size guard, YAML parsing (yaml_document.h),
// then the sections of the format (formats/internal/model_parser.h).
#include "formats/model_loader.h"
#include "ccma/internal/format.h"

#include <string>

#include <yaml-cpp/yaml.h>

#include "ccma/limits.h"
#include "formats/internal/model_parser.h"
#include "formats/internal/yaml_document.h"

namespace ccma {
namespace {


}  // namespace

Model LoadModelFromString(const std::string& text, const std::string& source_name,
                          std::vector<std::string>* warnings) {
  if (text.size() > kMaxModelFileBytes) {
    throw ModelError(source_name + ": larger than " + FormatMiB(kMaxModelFileBytes) +
                     " (the limit for a model file)");
  }
  const YAML::Node root = internal::ParseYamlText(text, source_name);
  try {
    return internal::ModelParser(source_name, warnings).Parse(root);
  } catch (const YAML::Exception& e) {  // a conversion we did not foresee
    throw ModelError(internal::WithLine(source_name, e.mark) + ": " + e.msg);
  }
}

Model LoadModel(const std::string& path, std::vector<std::string>* warnings) {
  std::string text;
  std::string error;
  if (!internal::ReadRegularFile(path, kMaxModelFileBytes, "model file", &text, &error)) {
    throw ModelError(error);
  }
  return LoadModelFromString(text, path, warnings);
}

}  // namespace ccma
