#pragma once
// Statistics for Monte Carlo tests: Pearson chi-square with the p-value from
// Boost.Math (support/p_values.cpp), pooling of sparse cells as in pbrt-v4's
// sampler tests.
#include <cstdint>
#include <span>
#include <vector>

#include "support/p_values.h"

namespace spectrace::testing {

struct ChiSquareResult {
  double statistic = 0.0;
  int degreesOfFreedom = 0;
  double pValue = 0.0;
  bool impossibleHit = false;  // a count in a cell of expected probability 0
};

// Pearson's test of observed counts against expected probabilities. Cells
// expected to hold fewer than `minExpected` are pooled (so the chi-square
// approximation holds); any count in a zero-probability cell is reported.
inline ChiSquareResult chiSquareTest(std::span<const uint64_t> observed, std::span<const double> probability,
                                     double minExpected = 5.0) {
  ChiSquareResult result;
  uint64_t n = 0;
  for (uint64_t c : observed) n += c;
  double pooledObserved = 0.0, pooledExpected = 0.0;
  int cells = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    const double expected = probability[i] * double(n);
    if (probability[i] == 0.0) {
      if (observed[i] != 0) result.impossibleHit = true;
      continue;
    }
    if (expected < minExpected) {
      pooledObserved += double(observed[i]);
      pooledExpected += expected;
      continue;
    }
    const double d = double(observed[i]) - expected;
    result.statistic += d * d / expected;
    ++cells;
  }
  if (pooledExpected > 0.0) {
    const double d = pooledObserved - pooledExpected;
    result.statistic += d * d / pooledExpected;
    ++cells;
  }
  result.degreesOfFreedom = cells - 1;
  if (result.degreesOfFreedom < 1) {
    result.pValue = 1.0;
    return result;
  }
  result.pValue = chiSquareUpperTail(result.statistic, result.degreesOfFreedom);
  return result;
}

}  // namespace spectrace::testing
