// The timed path of the controls in a trajectory CSV (`ccma trajectory` and
// `ccma plan` write them; `ccma dynamics` reads them): `time_s`, every
// control column of the model (viewer::TrajectoryControlColumns) and, when
// present, the reached end-effector point x_m, y_m, z_m.
//
// The file is untrusted: read through viewer::CsvReader (bounded, every cell
// a plain number), at most kMaxPathSteps + 1 rows, at least 2; times finite
// and strictly increasing; controls present and within kMaxMagnitude.
// Every message names the file, line and column (viewer::ViewInputError).
#ifndef CCMA_DOCUMENTS_CONTROL_PATH_CSV_H_
#define CCMA_DOCUMENTS_CONTROL_PATH_CSV_H_

#include <string>

#include "analyses/dynamics.h"
#include "ccma/model.h"

namespace ccma::documents {

ControlPath ReadControlPath(const Model& model, const std::string& csv_path);
// The same from the text of a CSV; `source` names it in messages.
ControlPath ReadControlPathText(const Model& model, const std::string& text, const std::string& source);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_CONTROL_PATH_CSV_H_
