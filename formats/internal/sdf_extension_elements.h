// ccma's own elements in an SDFormat file (<ccma:legged>, <ccma:actuated>,
// <ccma:end_effector>, written by `ccma export`) are the elements of ccma's
// XML namespace, kCcmaSdfNamespace (legged_extension.h), whatever prefix the file binds to it:
// `<sdf xmlns:c="https://ccma.dev/sdf">` makes <c:legged> ccma's, and a
// <ccma:legged> whose prefix is bound to another URI, or to none, is some
// other vocabulary's element, which ccma ignores as libsdformat does
// (issue 49: the prefix alone used to decide). libsdformat keeps such
// elements, their text and their xmlns attributes in its element tree.
#ifndef CCMA_FORMATS_INTERNAL_SDF_EXTENSION_ELEMENTS_H_
#define CCMA_FORMATS_INTERNAL_SDF_EXTENSION_ELEMENTS_H_

#include <string>
#include <utility>
#include <vector>

#include <sdf/Element.hh>

#include "formats/internal/legged_extension.h"

namespace ccma {
namespace internal {

// The children of `parent` that are ccma's element `local` ("legged"):
// named PREFIX:local with PREFIX bound to kCcmaSdfNamespace by the nearest
// xmlns:PREFIX on the child or an ancestor. In file order.
std::vector<sdf::ElementPtr> CcmaSdfChildren(const sdf::ElementPtr& parent, const std::string& local);

// For a message about a missing ccma element `local` under `parent`: why a
// child named PREFIX:local is not ccma's (" (<ccma:legged> here is bound to
// 'URI', not https://ccma.dev/sdf)"; an undeclared prefix says so), or ""
// when there is none.
std::string NotCcmaHint(const sdf::ElementPtr& parent, const std::string& local);

// The attributes of a ccma element (name, value; in file order), its
// namespace declarations left out. Throws ModelError "`where`: ..." when the
// element holds child elements or text: ccma's elements take attributes
// only (issue 49).
std::vector<std::pair<std::string, std::string>> CcmaSdfAttributes(const sdf::ElementPtr& element,
                                                                   const std::string& where);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_SDF_EXTENSION_ELEMENTS_H_
