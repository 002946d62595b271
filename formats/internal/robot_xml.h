// The XML ccma accepts in a robot file (URDF, SDFormat), checked before any
// XML parser sees the text.
//
// Two parsers read these files: TinyXML (ccma's own checks, and urdfdom for
// URDF, also inside libsdformat) and TinyXML-2 (libsdformat). They split a
// text into tokens differently at the edges of XML: TinyXML ends `<?x >` at
// the first '>' and TinyXML-2 at the next "?>"; `< a>` is an element to one
// and skipped markup to the other; TinyXML reads a UTF-8 lead byte as the
// start of up to 4 bytes, whatever they are. A check made on one
// tokenisation says nothing about the other (a file nested 100,000 deep
// after `<?x >`, or an <sdf> that libsdformat reads as a URDF, passed one).
// So a robot file must lie in a plain subset of XML that both read the same
// way, and the bounds are counted on it:
//  - bytes: valid UTF-8 without NUL or other control characters (tab, LF and
//    CR allowed), DEL, U+FEFF, U+FFFE or U+FFFF, except a byte-order mark as
//    the first character;
//  - an optional `<?xml ...?>` declaration at the very start (attributes
//    only), then comments and white space, one element named `root`, then
//    comments and white space only;
//  - no DOCTYPE, no processing instruction, no other `<!` or `<?` markup;
//  - tags `<name a="v" b='v'>`, `<name .../>` and `</name>` (white space
//    allowed before '>'), names [A-Za-z_][A-Za-z0-9_.:-]* (non-ASCII
//    characters allowed after the first), attribute values in quotes without
//    '<', closing names matching;
//  - inside elements: text, comments `<!-- -->` and CDATA sections.
#ifndef CCMA_FORMATS_INTERNAL_ROBOT_XML_H_
#define CCMA_FORMATS_INTERNAL_ROBOT_XML_H_

#include <cstddef>
#include <map>
#include <string>

namespace ccma {
namespace internal {

// Elements nested deeper than this are refused (TinyXML parses recursively;
// robot files nest about 6 deep; libsdformat's TinyXML-2 stops at 100).
constexpr int kMaxXmlNesting = 100;
// Elements per robot file (a 300-link URDF with visuals, collisions and
// inertials has about 10,000). Readers bound heavier elements further.
constexpr std::size_t kMaxRobotXmlElements = 100000;

struct RobotXmlSummary {
  struct Name {
    std::size_t count = 0;
    int first_line = 0;
  };
  std::size_t elements = 0;           // all elements, the root included
  std::map<std::string, Name> names;  // per element name
};

// Checks `text` as described above, with a root element named `root`.
// Returns the counts. Throws ModelError "source:LINE: what" (names quoted;
// "not valid XML: ..." for malformed XML, "not KIND: its root element is
// 'x', not <root>" for another root; kind e.g. "a URDF").
RobotXmlSummary CheckRobotXml(const std::string& text, const std::string& source, const std::string& root,
                              const std::string& kind);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_ROBOT_XML_H_
