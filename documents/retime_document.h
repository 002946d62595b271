// The document of `ccma retime` (docs/cli.md) and Python's `retime()`: the
// JSON summary of a retimed path (analyses/retime.h), and the retimed CSV:
// the input's text with only its time_s cells replaced.
#ifndef CCMA_DOCUMENTS_RETIME_DOCUMENT_H_
#define CCMA_DOCUMENTS_RETIME_DOCUMENT_H_

#include <string>
#include <vector>

#include "analyses/retime.h"
#include "documents/document.h"

namespace ccma::documents {

// feasible, rows, original_duration_s; when feasible duration_s,
// uniform_duration_s, method, verified_scale, limiting [{name, kind,
// share}]; when not, infeasible {row, line, time_s, control, kind, effort,
// limit} and a warning.
Document RetimeDocument(const RetimeReport& report, size_t rows);

// `input` (a trajectory CSV's text, as read) with the time_s cell of the
// row on lines[i] (from 1) replaced by times[i] (17 significant digits);
// every other byte as it was. Throws std::invalid_argument when a line or
// the time_s column is not there (the reader that gave `lines` found them).
std::string RetimedCsv(const std::string& input, const std::vector<int>& lines, const std::vector<double>& times);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_RETIME_DOCUMENT_H_
