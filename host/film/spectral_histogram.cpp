#include "film/spectral_histogram.h"

#include <fmt/format.h>

namespace spectrace {
namespace {

// "counts at pixel (x, y), bin b": where counter `index` of channel `c` sits.
std::string counterName(const SpectralHistogram& h, uint32_t c, size_t index) {
  const uint32_t perPixel = device::filmChannelCounters(c, h.bins);
  const size_t pixel = index / perPixel, counter = index % perPixel;
  std::string name = fmt::format("{} at pixel ({}, {})", filmChannelName(c), pixel % h.pixelsX, pixel / h.pixelsX);
  if (c == device::kFilmChannelBins) return name + fmt::format(", bin {}", counter);
  if (perPixel == 3) return name + fmt::format(", {}", "XYZ"[counter]);
  return name;
}

}  // namespace

std::optional<size_t> addChannel(uint64_t* mine, const uint64_t* theirs, size_t size, uint32_t counterWords) {
  if (counterWords == 1) {
    for (size_t i = 0; i < size; ++i) {
      uint64_t sum = 0;
      if (__builtin_add_overflow(mine[i], theirs[i], &sum)) return i;
      mine[i] = sum;
    }
    return std::nullopt;
  }
  for (size_t i = 0; i + 1 < size; i += 2) {
    uint64_t low = 0, high = 0;
    const bool carry = __builtin_add_overflow(mine[i], theirs[i], &low);
    if (__builtin_add_overflow(mine[i + 1], theirs[i + 1], &high) || __builtin_add_overflow(high, carry ? 1 : 0, &high))
      return i / 2;
    mine[i] = low;
    mine[i + 1] = high;
  }
  return std::nullopt;
}

void SpectralHistogram::merge(const SpectralHistogram& other) {
  if (!sameShape(other)) throw std::invalid_argument("cannot merge histograms of different shapes");
  uint64_t beams = 0;
  if (__builtin_add_overflow(countedBeams, other.countedBeams, &beams))
    throw CounterOverflow(fmt::format("counted_beams: {} + {} passes 2^64 - 1", countedBeams, other.countedBeams));
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) {  // every channel merges by exact addition
    std::vector<uint64_t>& mine = channel(c);
    if (const auto at = addChannel(mine.data(), other.channel(c).data(), mine.size(), counterWords()))
      throw CounterOverflow(fmt::format("{}: {} + {} passes 2^{} - 1, the most a counter holds",
                                        counterName(*this, c, *at), wideValue(counter(c, *at)),
                                        wideValue(other.counter(c, *at)), 64 * counterWords()));
  }
  countedBeams = beams;
}

}  // namespace spectrace
