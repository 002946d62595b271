// ccma's extension that makes a robot file's `floating` joint from the ground
// a legged base (docs/import.md, "Legged bases"): one element inside the
// joint, which urdfdom and libsdformat ignore, carrying the base's body,
//   URDF:     <ccma_legged body_height="0.45" height_limits="0.3 0.55"
//                          roll_limits="-0.25 0.25" pitch_limits="-0.25 0.25" footprint="0.7 0.3"/>
//   SDFormat: <ccma:legged .../> with the same attributes.
// body_height [m] is required; the limits ("lo hi": height m, roll and pitch
// rad) and the footprint ("length width", m) are optional, as the model
// file's body_limits and footprint are. The URDF and SDFormat writers write
// it, the readers read it back.
#ifndef CCMA_FORMATS_INTERNAL_LEGGED_EXTENSION_H_
#define CCMA_FORMATS_INTERNAL_LEGGED_EXTENSION_H_

#include <string>
#include <utility>
#include <vector>

#include "ccma/model.h"

namespace ccma {
namespace internal {

constexpr const char* kUrdfLeggedElement = "ccma_legged";
constexpr const char* kSdfLeggedElement = "ccma:legged";
// The XML namespace of ccma's SDFormat elements, which the writer binds to
// the prefix ccma on <sdf>; the reader goes by it, not by the prefix
// (formats/internal/sdf_extension_elements.h).
constexpr const char* kCcmaSdfNamespace = "https://ccma.dev/sdf";

// ` body_height="h" ...` (a leading space; limits and footprint only when
// given), numbers with 17 significant digits so that they read back exactly.
std::string LeggedAttributes(const LeggedBody& body);

// The body an extension element's attributes (name, value; in file order)
// describe. Checked as the model loader checks a legged base: every name
// known and given once, every number finite and within 1e4, body_height > 0,
// each limit's lo <= home <= hi (home: body_height, zero roll and pitch), the
// footprint's two sides > 0. Throws ModelError "WHERE: ATTRIBUTE: what".
LeggedBody ParseLeggedAttributes(const std::vector<std::pair<std::string, std::string>>& attributes,
                                 const std::string& where);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_LEGGED_EXTENSION_H_
