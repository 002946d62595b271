// A model written as SDFormat 1.7 (`ccma export --format=sdf`, docs/cli.md):
// one <model> whose joints keep their loops (SDFormat allows them when the
// links are posed in an assembled configuration; libsdformat 12 loads it).
//  * every body is a link of the same name posed in the model (= world)
//    frame at home, with its body frame;
//  * every joint keeps its name: revolute -> `revolute` with its limits, or
//    `continuous`; prismatic -> `prismatic` (with its limits if any); fixed ->
//    `fixed`; spherical -> `ball`; universal -> `universal` (<axis> fixed in
//    the parent, <axis2> in the child). The parent is the joint's first body
//    (world may only be a parent: a joint whose second body is world is
//    written the other way round, its axis negated so its coordinate keeps its
//    sign). The joint frame sits at the joint point with world orientation
//    at home (its pose is relative to the child link, SDFormat's default),
//    so axes read the same in the joint frame and in the world;
//  * a joint with q_home != 0 has <initial_position> q_home: the links are
//    posed at home, where every joint reads q_home;
//  * a wheeled mobile base B hangs from world by a joint `B_planar` of type
//    `planar` (normal z, frame at the base frame's origin), as in URDF; a
//    legged one by a joint `B_floating` of type `floating` holding ccma's
//    <ccma:legged .../> (formats/internal/legged_extension.h). SDFormat has
//    neither type: libsdformat reports "Joint type of planar is invalid" (or
//    floating) for each of them and loads the rest; ccma's SDFormat reader
//    accepts both from world;
//  * ccma's extension elements in <model> (namespace https://ccma.dev/sdf):
//    <ccma:actuated joints="..."/> (when there are any) names the actuated joints in file order
//    (the controls after the bases', whose joints come first in the
//    file, in base order), and <ccma:end_effector link=".." point="x y z"
//    controlled=".."/> the end-effector (point in the link frame, m).
// Numbers are written in the fewest digits (15 to 17) that read back to the same doubles.
#ifndef CCMA_FORMATS_SDFORMAT_WRITER_H_
#define CCMA_FORMATS_SDFORMAT_WRITER_H_

#include <string>

#include "ccma/model.h"

namespace ccma {

struct SdformatExport {
  std::string sdf;  // the SDFormat document
  int links = 0;    // <link> elements (world is not one): one per body
  int joints = 0;   // <joint> elements
  int loops = 0;    // independent loops of the joint graph: joints - links
};

// The model (any valid one, as LoadModel returns it) as SDFormat 1.7.
SdformatExport WriteSdformat(const Model& model);

}  // namespace ccma

#endif  // CCMA_FORMATS_SDFORMAT_WRITER_H_
