// A guard run on untrusted XML (URDF, SDFormat) before a parser sees it:
// TinyXML and TinyXML-2 parse elements recursively, so a file of a few
// hundred kilobytes nested 100,000 deep would overflow the stack.
#ifndef CCMA_FORMATS_INTERNAL_XML_NESTING_H_
#define CCMA_FORMATS_INTERNAL_XML_NESTING_H_

#include <string>

namespace ccma {
namespace internal {

// Elements nested deeper than this are rejected. Robot files nest about 6 deep.
constexpr int kMaxXmlNesting = 100;

// Throws ModelError "source:line: XML elements nested more than 100 deep"
// when an element in `text` lies deeper than kMaxXmlNesting. Comments,
// CDATA, processing instructions and declarations are skipped; quoted
// attribute values may contain '>'.
void CheckXmlNesting(const std::string& text, const std::string& source);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_XML_NESTING_H_
