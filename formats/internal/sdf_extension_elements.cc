#include "formats/internal/sdf_extension_elements.h"

#include <sdf/Param.hh>

#include "ccma/internal/format.h"
#include "formats/model_loader.h"

namespace ccma {
namespace internal {
namespace {

// The prefix of a qualified name "p:local" whose local part is `local`;
// false for any other name.
bool PrefixOf(const std::string& name, const std::string& local, std::string* prefix) {
  const std::size_t colon = name.find(':');
  if (colon == std::string::npos || colon == 0 || name.compare(colon + 1, std::string::npos, local) != 0) return false;
  *prefix = name.substr(0, colon);
  return true;
}

// The URI `prefix` is bound to at `element` (the nearest declaration on it or
// an ancestor); false when none declares it.
bool NamespaceOf(sdf::ElementPtr element, const std::string& prefix, std::string* uri) {
  const std::string declaration = "xmlns:" + prefix;
  for (int depth = 0; element && depth < 1000; ++depth, element = element->GetParent()) {
    if (element->HasAttribute(declaration)) {
      *uri = element->GetAttribute(declaration)->GetAsString();
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<sdf::ElementPtr> CcmaSdfChildren(const sdf::ElementPtr& parent, const std::string& local) {
  std::vector<sdf::ElementPtr> out;
  if (!parent) return out;
  for (sdf::ElementPtr child = parent->GetFirstElement(); child; child = child->GetNextElement()) {
    std::string prefix, uri;
    if (PrefixOf(child->GetName(), local, &prefix) && NamespaceOf(child, prefix, &uri) && uri == kCcmaSdfNamespace) {
      out.push_back(child);
    }
  }
  return out;
}

std::string NotCcmaHint(const sdf::ElementPtr& parent, const std::string& local) {
  if (!parent) return "";
  for (sdf::ElementPtr child = parent->GetFirstElement(); child; child = child->GetNextElement()) {
    std::string prefix, uri;
    if (!PrefixOf(child->GetName(), local, &prefix)) continue;
    const std::string name = Quote("<" + child->GetName() + ">");
    if (!NamespaceOf(child, prefix, &uri)) {
      return " (" + name + " here has an undeclared prefix: declare xmlns:" + Printable(prefix) + "=\"" +
             kCcmaSdfNamespace + "\")";
    }
    return " (" + name + " here is bound to " + Quote(uri) + ", not " + kCcmaSdfNamespace + ")";
  }
  return "";
}

std::vector<std::pair<std::string, std::string>> CcmaSdfAttributes(const sdf::ElementPtr& element,
                                                                   const std::string& where) {
  if (const sdf::ElementPtr child = element->GetFirstElement()) {
    throw ModelError(where + ": a child element " + Quote("<" + child->GetName() + ">") +
                     ": the element takes attributes only");
  }
  if (const sdf::ParamPtr text = element->GetValue()) {
    const std::string value = text->GetAsString();
    if (value.find_first_not_of(" \t\r\n") != std::string::npos) {
      throw ModelError(where + ": text " + Quote(value) + " inside: the element takes attributes only");
    }
  }
  std::vector<std::pair<std::string, std::string>> attributes;
  for (std::size_t i = 0; i < element->GetAttributeCount(); ++i) {
    const sdf::ParamPtr attribute = element->GetAttribute(static_cast<unsigned>(i));
    const std::string key = attribute->GetKey();
    if (key == "xmlns" || key.rfind("xmlns:", 0) == 0) continue;
    attributes.emplace_back(key, attribute->GetAsString());
  }
  return attributes;
}

}  // namespace internal
}  // namespace ccma
