// What an SDFormat file says beyond its model's links and joints, and what
// its defaults mean (formats/sdformat_reader.h): a Gazebo world's gravity,
// SDFormat's default inertial for a link that gives none, links gravity does
// not act on, and 1.11's computed inertials that Debian's libsdformat 12
// cannot compute. Each either sets the description or says so in a warning.
#ifndef CCMA_FORMATS_INTERNAL_SDFORMAT_WORLD_H_
#define CCMA_FORMATS_INTERNAL_SDFORMAT_WORLD_H_

#include <string>
#include <vector>

#include <sdf/Model.hh>
#include <sdf/Root.hh>
#include <tinyxml.h>

#include "formats/robot_description.h"

namespace ccma::internal {

// The file's one <model>, or the one model of its one <world> that is not
// static (a ground plane beside it is skipped, with a warning). Throws
// ModelError for none, several moving ones, a nested model, or more links
// or joints than ccma imports.
const sdf::Model& TheModel(const sdf::Root& root, const std::string& source, std::vector<std::string>* warnings);

// <inertial auto="true"> elements under `e`: one warning each, with its line.
void WarnOfComputedInertials(const TiXmlElement& e, const std::string& source, std::vector<std::string>* warnings);

// The links of `model` without <inertial> (they get SDFormat's default,
// 1 kg): one warning naming up to five.
void AddDefaultInertialsWarning(const sdf::Model& model, const std::string& source, RobotDescription* robot);

// The links of `model` with <gravity>false</gravity>: one warning.
void AddWeightlessLinksWarning(const sdf::Model& model, const std::string& source, RobotDescription* robot);

// A world's gravity as the robot's (a file of one <model>: nothing). Throws
// ModelError for a gravity that is not finite or beyond 1000 m/s^2.
void ReadWorldGravity(const sdf::Root& root, const std::string& source, RobotDescription* robot);

}  // namespace ccma::internal

#endif  // CCMA_FORMATS_INTERNAL_SDFORMAT_WORLD_H_
