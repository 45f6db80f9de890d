#include "film/pixel_variance.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace spectrace {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

double pixelRelativeVariance(device::WideCount total, device::WideCount squaredWeights, uint64_t beams,
                             uint64_t unitsPerBeam, size_t pixel) {
  if (beams == 0) throw std::invalid_argument("estimatedRelativeVariance: beams must be > 0");
  const double n = double(beams);
  const double units = double(unitsPerBeam);
  if (unitsPerBeam == 1 && (total.high != 0 || total.low > beams))
    throw std::invalid_argument("estimatedRelativeVariance: pixel " + std::to_string(pixel) + " has " +
                                std::to_string(total.low) + " counts, more than the " + std::to_string(beams) +
                                " beams");
  if (wideValue(total) == 0) return kNaN;
  // 1/C - 1/N = (N - C) / (C N), computed in this form so C == N gives 0 exactly.
  if (unitsPerBeam == 1) return double(beams - total.low) / (double(total.low) * n);
  // Weighted: with S1 = sum of weight ratios and S2 = sum of their
  // squares, Var/E^2 = (S2/N - (S1/N)^2) / (N (S1/N)^2) = S2/S1^2 - 1/N.
  const double s1 = realOf(total) / units, s2 = realOf(squaredWeights) / units;
  return std::max(0.0, s2 / (s1 * s1) - 1.0 / n);
}

std::vector<double> estimatedRelativeVariance(const SpectralHistogram& histogram, uint64_t beams) {
  if (beams == 0) throw std::invalid_argument("estimatedRelativeVariance: beams must be > 0");
  const size_t pixels = size_t(histogram.pixelsX) * histogram.pixelsY;
  const size_t words = histogram.counterWords();
  if (histogram.counts().size() != pixels * histogram.bins * words ||
      histogram.squaredWeightSums().size() != (histogram.isWeighted() ? pixels * words : 0))
    throw std::invalid_argument("estimatedRelativeVariance: histogram counts do not match its shape");
  std::vector<double> out(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    device::WideCount c{0, 0};
    for (uint32_t b = 0; b < histogram.bins; ++b) {
      const device::WideCount add = histogram.count(uint32_t(p), b);
      const uint64_t low = c.low + add.low;
      c.high += add.high + (low < c.low ? 1 : 0);
      c.low = low;
    }
    const device::WideCount squared =
        histogram.isWeighted() ? histogram.counter(device::kFilmChannelSquaredWeight, p) : device::WideCount{0, 0};
    out[p] = pixelRelativeVariance(c, squared, beams, histogram.unitsPerBeam, p);
  }
  return out;
}

}  // namespace spectrace
