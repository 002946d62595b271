// Model -> model file text (YAML, shared/model_format.md): what `ccma import`
// writes. Everything is written in world coordinates at home, numbers in the
// fewest digits (15 to 17) that read back exactly (FormatExact: 0.6, not
// 0.59999999999999998), so LoadModelFromString(WriteModelYaml(m)) gives back
// m's geometry to rounding. Every revolute and prismatic joint carries
// `q_home` (0 included). Omni bases are written with their default wheels
// (the wheel list is not written). Collision geometry is written when the
// model has it (`collision:` with every capsule, ignored pairs, `obstacles:`);
// a base's own `radius:` where it differs from base_radius.
#ifndef CCMA_FORMATS_MODEL_WRITER_H_
#define CCMA_FORMATS_MODEL_WRITER_H_

#include <string>

#include "ccma/model.h"

namespace ccma {

// The model file text for `model`; `header` (may be empty) is written first
// as YAML comments, one "# " per line.
std::string WriteModelYaml(const Model& model, const std::string& header = "");

}  // namespace ccma

#endif  // CCMA_FORMATS_MODEL_WRITER_H_
