// --obstacles=FILE.yaml (model_format.md, "Collision geometry and
// obstacles"): a file with only an `obstacles:` list, added to a loaded
// model by any command that moves the mechanism.
#ifndef CCMA_FORMATS_OBSTACLES_FILE_H_
#define CCMA_FORMATS_OBSTACLES_FILE_H_

#include <string>
#include <vector>

#include "ccma/model.h"

namespace ccma {

// Reads the obstacles of the file at `path` (a regular file of at most
// kMaxObstacleFileBytes) and appends them to model->collision.obstacles,
// which turns clearance on (model->collision.enabled). Names must differ
// from the model's bodies, bases and obstacles. A model whose bases stand
// too close at home for a default radius (collision.base_radius_unfit) is
// refused: it must give collision.base_radius. Throws ModelError
// "path:line: key: what" on any problem; unknown keys are appended to
// `warnings` (may be null) as the model loader does.
void AddObstaclesFromFile(const std::string& path, Model* model, std::vector<std::string>* warnings = nullptr);

// The same for the text of an obstacles file already in memory (at most
// kMaxObstacleFileBytes); `source` names it in messages ("source:line: key:
// what"). The model is changed only when the whole file is valid.
void AddObstaclesFromString(const std::string& text, const std::string& source, Model* model,
                            std::vector<std::string>* warnings = nullptr);

}  // namespace ccma

#endif  // CCMA_FORMATS_OBSTACLES_FILE_H_
