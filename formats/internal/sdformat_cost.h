// What libsdformat 12 will take to load a file, estimated from its elements
// (formats/internal/robot_xml.h counts them) before it sees any: it copies
// the whole description of an element (every child it may have, from
// SDFormat's specification) for each element it reads, about 1.2 KB per
// description node, so a <link> costs about 0.85 MB, a <model> 1.5 MB, a
// <world> 6 MB (measured with /usr/bin/time -v; docs/import.md).
#ifndef CCMA_FORMATS_INTERNAL_SDFORMAT_COST_H_
#define CCMA_FORMATS_INTERNAL_SDFORMAT_COST_H_

#include "formats/internal/robot_xml.h"

namespace ccma {
namespace internal {

// A file estimated above this is refused: libsdformat's peak memory then
// stays below 1 GB (measured with /usr/bin/time -v just under the bound:
// 700 empty links 0.60 GB, 98 <world>s 0.61 GB, 4,900 <collision>s, the
// element the estimate is least generous to, 0.79 GB).
constexpr double kMaxSdformatMegabytes = 850;

// The estimate, in MB (1 MB = 2^20 bytes): per element, 8 KB plus 1.6 KB per
// node of the largest description of that name in libsdformat's
// specification (8 KB for names it does not know). Generous by design: the
// measured cost is 1.1 to 1.5 KB per node.
double SdformatMegabytes(const RobotXmlSummary& summary);

// The estimate for `count` elements named `name`, for messages.
double SdformatMegabytes(const std::string& name, std::size_t count);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_SDFORMAT_COST_H_
