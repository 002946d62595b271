// A Gazebo world's own <include>s: the ground plane and the sun that almost
// every world file pulls in from Gazebo's model path. They name models
// outside the file, which are not the robot, and libsdformat would open the
// files they name (the only place where it opens a file of its own), so the
// SDFormat reader blanks them out of the text before libsdformat reads it,
// each with a warning. An <include> anywhere else (inside a model: part of
// the robot) is refused.
#ifndef CCMA_FORMATS_INTERNAL_WORLD_INCLUDES_H_
#define CCMA_FORMATS_INTERNAL_WORLD_INCLUDES_H_

#include <string>
#include <vector>

#include <tinyxml.h>

namespace ccma::internal {

// `text` (which `document` holds, parsed by TinyXML) with every <include>
// child of a <world> replaced by spaces, newlines kept (libsdformat's line
// numbers stay the file's); one warning per include ("source:line: <include>
// of 'uri' skipped: ..."). Throws ModelError "source:line: <include> is not
// supported ..." for an include elsewhere, or one the scan cannot place.
std::string BlankWorldIncludes(const TiXmlDocument& document, const std::string& text, const std::string& source,
                               std::vector<std::string>* warnings);

}  // namespace ccma::internal

#endif  // CCMA_FORMATS_INTERNAL_WORLD_INCLUDES_H_
