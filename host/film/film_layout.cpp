#include "film/film_layout.h"

#include <algorithm>
#include <stdexcept>

namespace spectrace {

void packDeviceCounters(const SpectralHistogram& histogram, const FilmLayout& film, size_t firstPixel,
                        std::span<uint64_t> out) {
  const uint32_t stride = film.countersPerPixel(), stored = film.storedBins, first = film.firstStoredBin;
  for (uint64_t p = 0; p < film.pixelCount(); ++p) {
    if (film.storesPixel(p)) continue;
    for (uint32_t b = 0; b < film.bins; ++b)
      if (histogram.counts[p * film.bins + b] != 0)
        throw std::invalid_argument("counts in pixels outside the stored window");
  }
  const uint32_t colour = device::colourCounterOffset(stored);
  const uint32_t squared = device::squaredWeightCounterOffset(stored, film.exactColour);
  for (size_t local = 0; local < out.size() / stride; ++local) {
    const size_t pixel = film.fullPixelOfStored(firstPixel + local);
    uint64_t* dst = out.data() + local * stride;
    const auto bins = histogram.counts.begin() + pixel * film.bins;
    for (uint32_t b = 0; b < film.bins; ++b) {
      if ((b < first || b >= first + stored) && bins[b] != 0)
        throw std::invalid_argument("counts in bins the trimmed spectrum does not store");
    }
    std::copy_n(bins + first, stored, dst);
    if (film.exactColour) std::copy_n(histogram.colourSums.begin() + pixel * 3, 3, dst + colour);
    if (film.weighted()) dst[squared] = histogram.squaredWeightSums[pixel];
  }
}

void unpackDeviceCounters(std::span<const uint64_t> counters, const FilmLayout& film, size_t firstPixel,
                          SpectralHistogram& histogram) {
  const uint32_t stride = film.countersPerPixel(), stored = film.storedBins;
  const uint32_t colour = device::colourCounterOffset(stored);
  const uint32_t squared = device::squaredWeightCounterOffset(stored, film.exactColour);
  for (size_t local = 0; local < counters.size() / stride; ++local) {
    const size_t pixel = film.fullPixelOfStored(firstPixel + local);
    const uint64_t* src = counters.data() + local * stride;
    std::copy(src, src + stored, histogram.counts.begin() + pixel * film.bins + film.firstStoredBin);
    if (film.exactColour) std::copy_n(src + colour, 3, histogram.colourSums.begin() + pixel * 3);
    if (film.weighted()) histogram.squaredWeightSums[pixel] = src[squared];
  }
}

}  // namespace spectrace
