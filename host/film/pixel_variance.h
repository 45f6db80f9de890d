#pragma once
// The render's own error estimate, from the counts alone: the film owns it so
// that develop can write it beside the image (error.E) and metrics can judge
// it against a reference.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "film/spectral_histogram.h"

namespace spectrace {

// Per-pixel relative variance of the irradiance estimated from the counts
// (the irradiance is irradiancePerCount x the pixel's total count). A pixel's
// total count C out of N = `beams` beams is binomial(N, p), so
// Var(E)/E^2 = (1 - p)/(N p); with p estimated by C/N: relVar = 1/C - 1/N.
// Weighted histograms (aimed area lights) use the squared-weight sums:
// relVar = S2/S1^2 - 1/N over the pixel's weight ratios, which reduces to the
// binomial form when every ratio is 1.
// C = 0: undefined, NaN (computeErrorMetrics skips and counts such pixels).
// Throws std::invalid_argument if beams == 0 or a pixel's count exceeds it.
std::vector<double> estimatedRelativeVariance(const SpectralHistogram& histogram, uint64_t beams);
// The same for one pixel, from its exact sums: total counts C, the
// squared-weight sum (weighted films only) and the units of a full-weight
// beam; `pixel` only names it in the error.
double pixelRelativeVariance(device::WideCount total, device::WideCount squaredWeights, uint64_t beams,
                             uint64_t unitsPerBeam, size_t pixel);

}  // namespace spectrace
