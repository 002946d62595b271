#include "formats/internal/world_includes.h"

#include <cstring>

#include "ccma/internal/format.h"
#include "formats/model_loader.h"

namespace ccma::internal {
namespace {

[[noreturn]] void Refuse(const std::string& source, int line) {
  throw ModelError(source + ":" + std::to_string(line) +
                   ": <include> is not supported: put the included model's links and joints in the file");
}

// Every <include> element under `e`, in document order.
void FindIncludes(const TiXmlElement& e, std::vector<const TiXmlElement*>* out) {
  for (const TiXmlElement* c = e.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
    if (std::strcmp(c->Value(), "include") == 0) out->push_back(c);
    FindIncludes(*c, out);
  }
}

// The byte offset of line `row` (1-based) of `text`; npos past the end.
std::size_t LineStart(const std::string& text, int row) {
  std::size_t at = 0;
  for (int r = 1; r < row; ++r) {
    at = text.find('\n', at);
    if (at == std::string::npos) return at;
    ++at;
  }
  return at;
}

// [begin, end) of the include element starting at line `row`: its start tag,
// to `/>` or to its `</include>` (includes do not nest); false when the
// text there is not one.
bool ElementSpan(const std::string& text, int row, std::size_t* begin, std::size_t* end) {
  const std::size_t line = LineStart(text, row);
  if (line == std::string::npos) return false;
  *begin = text.find("<include", line);
  const std::size_t next_line = text.find('\n', line);
  if (*begin == std::string::npos || (next_line != std::string::npos && *begin > next_line)) return false;
  const std::size_t close = text.find('>', *begin);
  if (close == std::string::npos) return false;
  if (text[close - 1] == '/') {
    *end = close + 1;
    return true;
  }
  const std::size_t tail = text.find("</include>", close);
  if (tail == std::string::npos) return false;
  *end = tail + std::strlen("</include>");
  return true;
}

}  // namespace

std::string BlankWorldIncludes(const TiXmlDocument& document, const std::string& text, const std::string& source,
                               std::vector<std::string>* warnings) {
  std::vector<const TiXmlElement*> includes;
  if (document.RootElement() != nullptr) FindIncludes(*document.RootElement(), &includes);
  std::string kept = text;
  for (const TiXmlElement* include : includes) {
    const TiXmlNode* parent = include->Parent();
    const bool in_world = parent != nullptr && std::strcmp(parent->Value(), "world") == 0;
    std::size_t begin = 0, end = 0;
    // Two includes on one line cannot be told apart by line: refused too.
    const TiXmlElement* twin = include->NextSiblingElement("include");
    if (!in_world || (twin != nullptr && twin->Row() == include->Row()) || !ElementSpan(kept, include->Row(), &begin, &end)) {
      Refuse(source, include->Row());
    }
    for (std::size_t i = begin; i < end; ++i) {
      if (kept[i] != '\n') kept[i] = ' ';
    }
    const TiXmlElement* uri = include->FirstChildElement("uri");
    const std::string name = uri != nullptr && uri->GetText() != nullptr ? uri->GetText() : "";
    warnings->push_back(source + ":" + std::to_string(include->Row()) + ": <include> of " + Quote(name) +
                        " skipped: ccma reads the models in the file, not those a world includes");
  }
  return kept;
}

}  // namespace ccma::internal
