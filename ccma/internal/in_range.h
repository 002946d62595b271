// Range checks of option values, shared by the options' IsValid().
#ifndef CCMA_INTERNAL_IN_RANGE_H_
#define CCMA_INTERNAL_IN_RANGE_H_

namespace ccma {

// lo <= value <= hi; false for NaN.
inline bool InRange(double value, double lo, double hi) { return value >= lo && value <= hi; }

}  // namespace ccma

#endif  // CCMA_INTERNAL_IN_RANGE_H_
