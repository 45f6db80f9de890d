#include "film/film_layout.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

namespace spectrace {

std::vector<StoredChannel> FilmLayout::channels() const {
  std::vector<StoredChannel> list;
  const uint32_t set = channelSet();
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) {
    if (!device::filmStoresChannel(set, c)) continue;
    const bool spectral = c == device::kFilmChannelBins;
    const uint32_t words = device::filmCounterWords(set);
    list.push_back({c, device::filmChannelOffset(c, storedBins, set), device::filmChannelCounters(c, storedBins) * words,
                    spectral ? firstStoredBin * words : 0, device::filmChannelCounters(c, bins) * words});
  }
  return list;
}

void packDeviceCounters(const SpectralHistogram& histogram, const FilmLayout& film, size_t firstPixel,
                        std::span<uint64_t> out) {
  const std::vector<StoredChannel> channels = film.channels();
  // What the device does not store must hold nothing: pixels outside the
  // window, and the bins of a trimmed spectrum outside its stored range.
  for (const StoredChannel& ch : channels) {
    const std::vector<uint64_t>& values = histogram.channel(ch.channel);
    for (uint64_t p = 0; p < film.pixelCount(); ++p) {
      const uint64_t* pixel = values.data() + p * ch.hostCounters;
      for (uint32_t i = 0; i < ch.hostCounters; ++i) {
        if (pixel[i] == 0) continue;
        if (!film.storesPixel(p))
          throw std::invalid_argument(fmt::format("{} in pixels outside the stored window", filmChannelName(ch.channel)));
        if (i < ch.hostFirst || i >= ch.hostFirst + ch.counters)
          throw std::invalid_argument("counts in bins the trimmed spectrum does not store");
      }
    }
  }
  const uint32_t stride = film.countersPerPixel();
  for (size_t local = 0; local < out.size() / stride; ++local) {
    const size_t pixel = film.fullPixelOfStored(firstPixel + local);
    for (const StoredChannel& ch : channels)
      std::copy_n(histogram.channel(ch.channel).begin() + pixel * ch.hostCounters + ch.hostFirst, ch.counters,
                  out.data() + local * stride + ch.deviceOffset);
  }
}

void unpackDeviceCounters(std::span<const uint64_t> counters, const FilmLayout& film, size_t firstPixel,
                          SpectralHistogram& histogram) {
  const std::vector<StoredChannel> channels = film.channels();
  const uint32_t stride = film.countersPerPixel();
  for (size_t local = 0; local < counters.size() / stride; ++local) {
    const size_t pixel = film.fullPixelOfStored(firstPixel + local);
    for (const StoredChannel& ch : channels)
      std::copy_n(counters.data() + local * stride + ch.deviceOffset, ch.counters,
                  histogram.channel(ch.channel).begin() + pixel * ch.hostCounters + ch.hostFirst);
  }
}

}  // namespace spectrace
