#include "film/pixel_variance.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace spectrace {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

double pixelRelativeVariance(uint64_t total, uint64_t squaredWeights, uint64_t beams, uint64_t unitsPerBeam,
                             size_t pixel) {
  if (beams == 0) throw std::invalid_argument("estimatedRelativeVariance: beams must be > 0");
  const double n = double(beams);
  const double units = double(unitsPerBeam);
  if (double(total) > n * units)
    throw std::invalid_argument("estimatedRelativeVariance: pixel " + std::to_string(pixel) + " has " +
                                std::to_string(total) + " counts, more than the " + std::to_string(beams) +
                                " beams can carry");
  if (total == 0) return kNaN;
  // 1/C - 1/N = (N - C) / (C N), computed in this form so C == N gives 0 exactly.
  if (unitsPerBeam == 1) return double(beams - total) / (double(total) * n);
  // Weighted: with S1 = sum of weight ratios and S2 = sum of their
  // squares, Var/E^2 = (S2/N - (S1/N)^2) / (N (S1/N)^2) = S2/S1^2 - 1/N.
  const double s1 = double(total) / units, s2 = double(squaredWeights) / units;
  return std::max(0.0, s2 / (s1 * s1) - 1.0 / n);
}

std::vector<double> estimatedRelativeVariance(const SpectralHistogram& histogram, uint64_t beams) {
  if (beams == 0) throw std::invalid_argument("estimatedRelativeVariance: beams must be > 0");
  const size_t pixels = size_t(histogram.pixelsX) * histogram.pixelsY;
  if (histogram.counts().size() != pixels * histogram.bins ||
      histogram.squaredWeightSums().size() != (histogram.isWeighted() ? pixels : 0))
    throw std::invalid_argument("estimatedRelativeVariance: histogram counts do not match its shape");
  std::vector<double> out(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    uint64_t c = 0;
    for (uint32_t b = 0; b < histogram.bins; ++b) c += histogram.counts()[p * histogram.bins + b];
    out[p] = pixelRelativeVariance(c, histogram.isWeighted() ? histogram.squaredWeightSums()[p] : 0, beams,
                                   histogram.unitsPerBeam, p);
  }
  return out;
}

}  // namespace spectrace
