#include "formats/internal/xml_nesting.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "formats/model_loader.h"

namespace ccma {
namespace internal {
namespace {

// Position just past `terminator` at or after `from` (text.size() if absent).
std::size_t Past(const std::string& text, std::size_t from, const char* terminator) {
  const std::size_t at = text.find(terminator, from);
  return at == std::string::npos ? text.size() : at + std::strlen(terminator);
}

// Position just past the '>' closing the tag that starts at `from`, quotes
// respected; sets *self_closing when the tag ends with "/>".
std::size_t PastTag(const std::string& text, std::size_t from, bool* self_closing) {
  char quote = 0;
  for (std::size_t i = from; i < text.size(); ++i) {
    const char c = text[i];
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '>') {
      *self_closing = i > from && text[i - 1] == '/';
      return i + 1;
    }
  }
  *self_closing = true;
  return text.size();
}

}  // namespace

void CheckXmlNesting(const std::string& text, const std::string& source) {
  int depth = 0;
  std::size_t i = 0;
  while ((i = text.find('<', i)) != std::string::npos) {
    if (text.compare(i, 4, "<!--") == 0) {
      i = Past(text, i, "-->");
    } else if (text.compare(i, 9, "<![CDATA[") == 0) {
      i = Past(text, i, "]]>");
    } else if (text.compare(i, 2, "<?") == 0) {
      i = Past(text, i, "?>");
    } else if (text.compare(i, 2, "<!") == 0 || text.compare(i, 2, "</") == 0) {
      if (text[i + 1] == '/') depth = std::max(0, depth - 1);
      i = Past(text, i, ">");
    } else {
      bool self_closing = false;
      const std::size_t end = PastTag(text, i + 1, &self_closing);
      if (!self_closing && ++depth > kMaxXmlNesting) {
        const long line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(i), '\n');
        throw ModelError(source + ":" + std::to_string(line) + ": XML elements nested more than " +
                         std::to_string(kMaxXmlNesting) + " deep");
      }
      i = end;
    }
  }
}

}  // namespace internal
}  // namespace ccma
