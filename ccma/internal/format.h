// Numbers in messages: %g, so that 1e-20 reads 1e-20 and not 0.000000.
#ifndef CCMA_INTERNAL_FORMAT_H_
#define CCMA_INTERNAL_FORMAT_H_

#include <cstdio>
#include <string>

namespace ccma {

// `value` with printf's %.<digits>g.
inline std::string FormatG(double value, int digits = 6) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

}  // namespace ccma

#endif  // CCMA_INTERNAL_FORMAT_H_
