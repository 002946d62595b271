#include "formats/internal/magnitude_checks.h"

#include <cmath>
#include <cstring>

#include "ccma/internal/format.h"

namespace ccma {
namespace internal {

void MagnitudeChecks::Record(Finding* finding, double value, int line, const std::string& path) {
  // Only the first one is named: building its location is all it costs.
  if (finding->count++ > 0) return;
  finding->where = source_ + (line >= 0 ? ":" + std::to_string(line + 1) : "") + ": " + path;
  finding->value = value;
}

void MagnitudeChecks::See(double value, const char* unit, int line, const std::string& path) {
  if (std::strcmp(unit, "m") == 0 && std::abs(value) > kImplausibleLength) {
    Record(&lengths_, value, line, path);
  } else if (std::strcmp(unit, "rad") == 0 && std::abs(value) > kImplausibleAngle) {
    Record(&angles_, value, line, path);
  }
}

void MagnitudeChecks::AppendWarnings(std::vector<std::string>* warnings) const {
  if (lengths_.count > 0) {
    warnings->push_back(lengths_.where + ": " + FormatG(lengths_.value) +
                        " m is implausible for a mobile mechanism; are the lengths in millimetres? (" +
                        std::to_string(lengths_.count) + (lengths_.count == 1 ? " length" : " lengths") +
                        " above " + FormatG(kImplausibleLength) + " m)");
  }
  if (angles_.count > 0) {
    warnings->push_back(angles_.where + ": " + FormatG(angles_.value) +
                        " rad is more than a full turn; is the angle in degrees? (" +
                        std::to_string(angles_.count) + (angles_.count == 1 ? " angle" : " angles") +
                        " above 2 pi)");
  }
}

}  // namespace internal
}  // namespace ccma
