// The document of `ccma dynamics` (docs/cli.md) and Python's `dynamics()`:
// the JSON summary of inverse dynamics along a path (analyses/dynamics.h)
// and its per-row table (the --out CSV).
#ifndef CCMA_DOCUMENTS_DYNAMICS_DOCUMENT_H_
#define CCMA_DOCUMENTS_DYNAMICS_DOCUMENT_H_

#include <string>
#include <vector>

#include "analyses/dynamics.h"
#include "ccma/model.h"
#include "documents/document.h"
#include "documents/table.h"

namespace ccma::documents {

// time_s, the effort columns (viewer::EffortColumns), kinetic_J, potential_J, power_W; one row per
// path row (empty effort cells where a row did not assemble).
Table DynamicsTable(const Model& model, const DynamicsReport& report);

// rows, duration_s, assembled, actuators [{name, kind, peak_effort,
// peak_time_s, rms_effort, limit, peak_rate, rate_limit, within_limits}], within_limits, limiting,
// energy_J, max_power_W, not_assembled_rows, max_rate_inconsistency; the
// warnings (rows not assembled, limits exceeded, inconsistent rates).
Document DynamicsDocument(const DynamicsReport& report);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_DYNAMICS_DOCUMENT_H_
