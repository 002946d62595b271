// ParseYamlText: nesting guard, then yaml-cpp (yaml_document.h).
#include "formats/internal/yaml_document.h"

#include <algorithm>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <yaml-cpp/depthguard.h>

#include "ccma/internal/format.h"
#include "formats/internal/library_message.h"

#include "formats/model_loader.h"

namespace ccma {
namespace internal {
namespace {

// Flow collections ([...], {...}) nested deeper than this are rejected before
// yaml-cpp sees them. yaml-cpp 0.7 itself stops any nesting (flow or block)
// with YAML::DeepRecursion after a few hundred levels, but says only "bad file".
constexpr int kMaxFlowNesting = 256;

// Rejects flow collections nested deeper than kMaxFlowNesting, counting every
// bracket outside comments (brackets inside quoted strings count too, which
// only matters for text no model file contains).
void CheckFlowNesting(const std::string& text, const std::string& source) {
  int depth = 0;
  int line = 1;
  bool comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      comment = false;
    } else if (comment) {
      continue;
    } else if (c == '#' && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t' ||
                            text[i - 1] == '\n')) {
      comment = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxFlowNesting) {
        throw ModelError(source + ":" + std::to_string(line) + ": not valid YAML: nested more than " +
                         std::to_string(kMaxFlowNesting) + " levels deep");
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

// Throws when a mapping names a key twice: yaml-cpp keeps both pairs and a
// lookup silently takes the first, so a repeated `obstacles:` or `name:` would
// be ignored without a word. Walks with an explicit stack; an aliased node
// (the same mark) is walked once, so anchors cannot multiply the work.
void CheckDuplicateKeys(const YAML::Node& root, const std::string& source) {
  std::set<std::pair<int, int>> walked;  // (position, type) of collections seen
  std::vector<YAML::Node> stack = {root};
  while (!stack.empty()) {
    const YAML::Node node = stack.back();
    stack.pop_back();
    if (!node.IsMap() && !node.IsSequence()) continue;
    if (!walked.insert({node.Mark().pos, static_cast<int>(node.Type())}).second) continue;
    std::unordered_map<std::string, int> first_line;
    for (auto it = node.begin(); it != node.end(); ++it) {
      if (node.IsSequence()) {
        stack.push_back(*it);
        continue;
      }
      stack.push_back(it->first);
      stack.push_back(it->second);
      if (!it->first.IsScalar()) continue;
      const int line = it->first.Mark().line + 1;
      const auto [at, inserted] = first_line.emplace(it->first.Scalar(), line);
      if (!inserted) {
        throw ModelError(WithLine(source, it->first.Mark()) + ": key " + Quote(it->first.Scalar()) +
                         " given twice in one mapping (first at line " + std::to_string(at->second) +
                         "); remove one");
      }
    }
  }
}

// The 1-based line of the `---` that starts the document whose content
// begins at `content` (its mark), looked for after `after` (where the
// document before it began); the content's own line when there is none
// (a document after `...` needs no `---`).
int DocumentStartLine(const std::string& text, const YAML::Mark& content, std::size_t after) {
  int line = 1, found = content.line + 1;
  for (std::size_t at = 0; at < text.size() && at < static_cast<std::size_t>(content.pos); ++at) {
    const bool line_start = at == 0 || text[at - 1] == '\n';
    const bool marker = text.compare(at, 3, "---") == 0 &&
                        (at + 3 == text.size() || std::string(" \t\r\n").find(text[at + 3]) != std::string::npos);
    if (line_start && at > after && marker) found = line;
    if (text[at] == '\n') ++line;
  }
  return found;
}

// Throws when `text` holds more than one YAML document: yaml-cpp's Load
// reads the first and ignores the rest silently, malformed or not (issue 49).
// A later document that is not valid YAML is refused by LoadAll itself.
void CheckOneDocument(const std::vector<YAML::Node>& documents, const std::string& text, const std::string& source) {
  if (documents.size() < 2) return;
  const auto first = static_cast<std::size_t>(std::max(0, documents[0].Mark().pos));
  const int line = DocumentStartLine(text, documents[1].Mark(), first);
  throw ModelError(source + ":" + std::to_string(line) + ": a second YAML document: the file must hold exactly one " +
                   "(remove everything from this line on)");
}

}  // namespace

std::string WithLine(const std::string& source, const YAML::Mark& mark) {
  return mark.line >= 0 ? source + ":" + std::to_string(mark.line + 1) : source;
}

YAML::Node ParseYamlText(const std::string& text, const std::string& source) {
  CheckFlowNesting(text, source);
  try {
    const std::vector<YAML::Node> documents = YAML::LoadAll(text);  // every document, so later ones are seen
    CheckOneDocument(documents, text, source);
    const YAML::Node root = documents.empty() ? YAML::Node() : documents.front();
    CheckDuplicateKeys(root, source);
    return root;
  } catch (const YAML::DeepRecursion& e) {
    throw ModelError(WithLine(source, e.mark) + ": not valid YAML: nested too deeply (" +
                     std::to_string(e.depth()) + " levels)");
  } catch (const YAML::ParserException& e) {
    throw ModelError(WithLine(source, e.mark) + ": not valid YAML: " + LibraryMessage(e.msg));
  } catch (const YAML::Exception& e) {
    throw ModelError(WithLine(source, e.mark) + ": cannot read the YAML: " + LibraryMessage(e.msg));
  }
}

}  // namespace internal
}  // namespace ccma
