// Valid but implausible magnitudes in a model file: lengths that suggest a
// model written in millimetres, angles that suggest degrees. These are
// warnings, not errors: the documented ranges (ccma/limits.h) decide what
// loads, and a 350 m mechanism is allowed; it is just rarely what was meant.
//
// Internal to the library: formats/model_loader.h is the public API.
#ifndef CCMA_FORMATS_INTERNAL_MAGNITUDE_CHECKS_H_
#define CCMA_FORMATS_INTERNAL_MAGNITUDE_CHECKS_H_

#include <string>
#include <vector>

namespace ccma {
namespace internal {

// Lengths [m] whose magnitude is above this look like millimetres: the
// bundled models stay within 1.2 m of the origin, and a mechanism of a few
// decimetres written in millimetres has coordinates of hundreds.
constexpr double kImplausibleLength = 100.0;
// Angles [rad] whose magnitude is above this (a full turn, plus slack for a
// rounded 2 pi such as 6.2832) look like degrees.
constexpr double kImplausibleAngle = 2 * 3.14159265358979323846 + 1e-3;

// Collects the implausible values of one model file, in the order read.
class MagnitudeChecks {
 public:
  explicit MagnitudeChecks(std::string source) : source_(std::move(source)) {}

  // Looks at `value`, read at key path `path` on 0-based line `line` (-1 when
  // YAML gives none), in `unit`: "m" (a length), "rad" (an angle); any other
  // unit is not checked.
  void See(double value, const char* unit, int line, const std::string& path);

  // At most one warning per kind (lengths, angles), naming the first
  // implausible value of that kind and how many there were, e.g.
  //   m.yaml:7: bodies[2].position[2]: 350 m is implausible for a mobile
  //   mechanism; are the lengths in millimetres? (12 lengths above 100 m)
  // (one line). Appended to `warnings`.
  void AppendWarnings(std::vector<std::string>* warnings) const;

 private:
  struct Finding {
    int count = 0;
    std::string where;  // "source:line: path" of the first one
    double value = 0;   // the first one
  };
  void Record(Finding* finding, double value, int line, const std::string& path);

  std::string source_;
  Finding lengths_;
  Finding angles_;
};

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_MAGNITUDE_CHECKS_H_
