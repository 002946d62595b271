// Links that are frames, not bodies (the closure file's `frames`, which
// `ccma export --format=urdf` writes): URDF's tree needs a link wherever a
// joint's frame is not a body's frame (a joint away from the body's origin,
// the two sides of a cut joint), and the model had no such bodies. Each
// listed link is fused into the link it is welded to, by a fixed joint or a
// 6d closure, so that the import gives back the model's own bodies: every
// joint and closure that named it names that link instead (their geometry is
// in world coordinates, so nothing moves), the weld itself goes, and so does
// a closure left joining a link to itself.
#ifndef CCMA_FORMATS_INTERNAL_FRAME_LINKS_H_
#define CCMA_FORMATS_INTERNAL_FRAME_LINKS_H_

#include <string>
#include <vector>

#include "formats/robot_description.h"

namespace ccma::internal {

// Fuses every link of `frames` into its body. Throws ModelError "where: ..."
// for an unknown link, a link with a mass, meshes or the end-effector, one
// welded to nothing, or the world.
void FuseFrameLinks(const std::vector<std::string>& frames, const std::string& where, RobotDescription* robot);

}  // namespace ccma::internal

#endif  // CCMA_FORMATS_INTERNAL_FRAME_LINKS_H_
