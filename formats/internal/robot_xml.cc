#include "formats/internal/robot_xml.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "ccma/internal/format.h"
#include "formats/model_loader.h"

namespace ccma {
namespace internal {
namespace {

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool IsNameStart(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }
bool IsNameChar(char c) {
  return IsNameStart(c) || (c >= '0' && c <= '9') || c == '.' || c == '-' || c == ':' ||
         static_cast<unsigned char>(c) >= 0x80;
}

// Bytes of the character at text[i] when it is allowed (see the header),
// else 0. Strict UTF-8: no overlong forms, surrogates or truncated ones, so
// that TinyXML's lead-byte lengths never swallow an ASCII '<'.
std::size_t CharLength(const std::string& text, std::size_t i) {
  const unsigned char c = static_cast<unsigned char>(text[i]);
  if (c < 0x80) return (c >= 0x20 && c != 0x7f) || c == '\t' || c == '\n' || c == '\r' ? 1 : 0;
  const std::size_t n = c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
  if (n == 0 || i + n > text.size()) return 0;
  unsigned long code = c & (n == 2 ? 0x1f : n == 3 ? 0x0f : 0x07);
  for (std::size_t k = 1; k < n; ++k) {
    const unsigned char d = static_cast<unsigned char>(text[i + k]);
    if ((d & 0xc0) != 0x80) return 0;
    code = (code << 6) | (d & 0x3f);
  }
  const unsigned long least = n == 2 ? 0x80 : n == 3 ? 0x800 : 0x10000;
  const bool bad = code < least || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff) || code == 0xfeff ||
                   code == 0xfffe || code == 0xffff;
  return bad ? 0 : n;
}

// One pass over the text; pos_ only moves forward.
class Scanner {
 public:
  Scanner(const std::string& text, const std::string& source) : text_(text), source_(source) {}
  RobotXmlSummary Run(const std::string& root, const std::string& kind);

 private:
  bool At(const char* s) const { return text_.compare(pos_, std::strlen(s), s) == 0; }
  char Peek(std::size_t ahead = 0) const { return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0'; }
  bool AtStartTag() const { return Peek() == '<' && IsNameStart(Peek(1)); }
  void SkipSpace() {
    while (pos_ < text_.size() && IsSpace(text_[pos_])) ++pos_;
  }
  int LineAt(std::size_t at);
  [[noreturn]] void Fail(std::size_t at, const std::string& what);
  std::string What() const;
  void CheckBytes();
  void SkipPast(std::size_t from, const char* end, const char* what);
  bool Misc();
  std::string ReadName();
  void Attribute(const char* forbidden);
  void Declaration();
  std::string StartTag(bool* empty);
  void CloseTag(std::vector<std::string>* open);
  void Elements(const std::string& root, const std::string& kind, RobotXmlSummary* summary);

  const std::string& text_;
  const std::string& source_;
  std::size_t pos_ = 0;
  std::size_t counted_ = 0;  // LineAt: newlines counted up to here
  int line_ = 1;
};

int Scanner::LineAt(std::size_t at) {
  if (at < counted_) counted_ = 0, line_ = 1;
  for (; counted_ < at && counted_ < text_.size(); ++counted_) line_ += text_[counted_] == '\n';
  return line_;
}

void Scanner::Fail(std::size_t at, const std::string& what) {
  throw ModelError(source_ + ":" + std::to_string(LineAt(at)) + ": " + what);
}

// What lies at pos_, for a message.
std::string Scanner::What() const {
  if (pos_ >= text_.size()) return "the end of the file";
  if (At("<?")) return "a processing instruction ('<?')";
  if (At("<!DOCTYPE")) return "a DOCTYPE";
  if (At("<![CDATA[")) return "a CDATA section";
  if (At("<!")) return "'<!' markup";
  if (At("</")) return "a closing tag";
  if (Peek() == '<') return "a '<' that does not start a tag";
  return "text";
}

void Scanner::CheckBytes() {
  pos_ = text_.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // a byte-order mark
  for (std::size_t i = pos_; i < text_.size();) {
    const std::size_t n = CharLength(text_, i);
    if (n == 0) {
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02x", static_cast<unsigned char>(text_[i]));
      Fail(i, std::string("byte ") + byte +
                  " is not allowed (a robot file must be UTF-8 text without control characters)");
    }
    i += n;
  }
}

// pos_ just past the first `end` at or after `from`.
void Scanner::SkipPast(std::size_t from, const char* end, const char* what) {
  const std::size_t at = text_.find(end, from);
  if (at == std::string::npos) Fail(pos_, std::string("not valid XML: ") + what + " not closed (no '" + end + "')");
  pos_ = at + std::strlen(end);
}

// White space and one comment outside the root element; false when
// something else follows.
bool Scanner::Misc() {
  SkipSpace();
  if (!At("<!--")) return false;
  SkipPast(pos_ + 4, "-->", "comment");
  return true;
}

std::string Scanner::ReadName() {
  if (!IsNameStart(Peek())) Fail(pos_, "not valid XML: expected a name ([A-Za-z_] first), found " + What());
  const std::size_t start = pos_;
  while (pos_ < text_.size() && IsNameChar(text_[pos_])) ++pos_;
  return text_.substr(start, pos_ - start);
}

// name="value" or name='value', the value without `forbidden` characters.
void Scanner::Attribute(const char* forbidden) {
  ReadName();
  SkipSpace();
  if (Peek() != '=') Fail(pos_, "not valid XML: expected '=' after an attribute name");
  ++pos_;
  SkipSpace();
  const char quote = Peek();
  if (quote != '"' && quote != '\'') Fail(pos_, "not valid XML: attribute values must be in quotes");
  const std::size_t end = text_.find(quote, pos_ + 1);
  if (end == std::string::npos) Fail(pos_, "not valid XML: attribute value not closed");
  const auto first = text_.begin() + static_cast<long>(pos_) + 1, last = text_.begin() + static_cast<long>(end);
  const auto bad = std::find_first_of(first, last, forbidden, forbidden + std::strlen(forbidden));
  if (bad != last) Fail(pos_, std::string("'") + *bad + "' inside an attribute value (not allowed in a robot file)");
  pos_ = end + 1;
}

// `<?xml name="value" ...?>` at the very start.
void Scanner::Declaration() {
  pos_ += 5;
  for (;;) {
    const std::size_t before = pos_;
    SkipSpace();
    if (At("?>")) break;
    if (pos_ == before || !IsNameStart(Peek())) {
      Fail(pos_, "the <?xml ...?> declaration may hold only attributes (name=\"value\")");
    }
    Attribute("<>?");
  }
  pos_ += 2;
}

// `<name a="v" ...>` (*empty false) or `<name .../>` (*empty true) at pos_.
std::string Scanner::StartTag(bool* empty) {
  ++pos_;
  const std::string name = ReadName();
  for (;;) {
    const std::size_t before = pos_;
    SkipSpace();
    *empty = At("/>");
    if (*empty || Peek() == '>') break;
    if (pos_ == before || !IsNameStart(Peek())) {
      Fail(pos_, "not valid XML: in tag <" + Printable(name) + ">: expected an attribute (name=\"value\"), '>' or '/>'");
    }
    Attribute("<");
  }
  pos_ += *empty ? 2 : 1;
  return name;
}

// `</name>` (white space allowed before '>') closing open->back().
void Scanner::CloseTag(std::vector<std::string>* open) {
  const std::size_t start = pos_;
  pos_ += 2;
  const std::string name = ReadName();
  SkipSpace();
  if (Peek() != '>') Fail(pos_, "not valid XML: expected '>' to end the closing tag </" + Printable(name) + ">");
  ++pos_;
  if (name != open->back()) Fail(start, "not valid XML: closing tag " + Quote(name) + " does not match element " + Quote(open->back()));
  open->pop_back();
}

// The root element and everything in it, without recursion.
void Scanner::Elements(const std::string& root, const std::string& kind, RobotXmlSummary* summary) {
  std::vector<std::string> open;
  do {
    const std::size_t start = pos_;
    if (AtStartTag()) {
      bool empty = false;
      const std::string name = StartTag(&empty);
      if (++summary->elements == 1 && name != root) {
        Fail(start, "not " + kind + ": its root element is " + Quote(name) + ", not <" + root + ">");
      }
      if (summary->elements > kMaxRobotXmlElements) {
        Fail(start, "more than " + std::to_string(kMaxRobotXmlElements) + " elements (the bound for a robot file)");
      }
      RobotXmlSummary::Name& counted = summary->names[name];
      if (counted.count++ == 0) counted.first_line = LineAt(start);
      if (!empty) open.push_back(name);
      if (open.size() > static_cast<std::size_t>(kMaxXmlNesting)) {
        Fail(start, "XML elements nested more than " + std::to_string(kMaxXmlNesting) + " deep");
      }
    } else if (At("</")) {
      CloseTag(&open);
    } else if (At("<!--")) {
      SkipPast(pos_ + 4, "-->", "comment");
    } else if (At("<![CDATA[")) {
      SkipPast(pos_ + 9, "]]>", "CDATA section");
    } else if (Peek() == '<') {
      Fail(pos_, What() + " inside element " + Quote(open.back()) + " is not allowed in a robot file");
    } else {
      pos_ = text_.find('<', pos_);
      if (pos_ == std::string::npos) Fail(text_.size(), "not valid XML: element " + Quote(open.back()) + " is not closed");
    }
  } while (!open.empty());
}

RobotXmlSummary Scanner::Run(const std::string& root, const std::string& kind) {
  CheckBytes();
  if (At("<?xml") && IsSpace(Peek(5))) Declaration();
  while (Misc()) {
  }
  if (!AtStartTag()) {
    Fail(pos_, "expected the root element <" + root + ">, found " + What() +
                   " (a robot file holds an optional <?xml ...?> declaration at its very start, comments "
                   "and one root element)");
  }
  RobotXmlSummary summary;
  Elements(root, kind, &summary);
  while (Misc()) {
  }
  if (pos_ < text_.size()) {
    Fail(pos_, "found " + What() + " after the root element <" + root +
                   "> (only comments and white space may follow it)");
  }
  return summary;
}

}  // namespace

RobotXmlSummary CheckRobotXml(const std::string& text, const std::string& source, const std::string& root,
                              const std::string& kind) {
  return Scanner(text, source).Run(root, kind);
}

}  // namespace internal
}  // namespace ccma
