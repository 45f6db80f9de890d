#pragma once
// Per-pixel spectral histogram: exact integer counts, [pixel][bin], pixels
// row-major from the top-left of the upright image. Integer counts make sums
// order-independent and bit-reproducible, so partial renders merge exactly.
// A plain film's counters are one 64-bit word; a weighted film's are two
// (WideCount: low word, high word; device_shared.h).
#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "device_shared.h"

namespace spectrace {

// A channel's name in state files and messages.
inline const char* filmChannelName(uint32_t c) {
  return c < device::kFilmChannelCount ? device::kFilmChannelNames[c] : "?";
}

// A counter's exact value, and near it in double.
inline unsigned __int128 wideValue(device::WideCount w) { return (unsigned __int128)w.high << 64 | w.low; }
inline double realOf(device::WideCount w) { return double(w.high) * 0x1p64 + double(w.low); }

// A merge that would carry a counter past what it holds (2^64 - 1, or
// 2^128 - 1 in two words), where it would wrap to a small count. The message
// names the channel, pixel and bin, and both values.
struct CounterOverflow : std::overflow_error {
  using std::overflow_error::overflow_error;
};

// Adds `size` words of one channel's counters, `theirs` to `mine`, counter
// by counter (`counterWords` words each, low word first, with its carry),
// up to the first whose sum would overflow: its index among the counters
// (that counter and the ones after it left as they were), or nullopt when
// every one was added. The one place that knows a channel's counter width.
std::optional<size_t> addChannel(uint64_t* mine, const uint64_t* theirs, size_t size, uint32_t counterWords);

struct SpectralHistogram {
  uint32_t pixelsX = 0, pixelsY = 0, bins = 0;
  // What one full-weight beam adds to its bin: 1 (plain hit counts) or, when
  // beams carry fractional weights, kWeightUnitsFractional.
  uint64_t unitsPerBeam = 1;
  // Each channel's counters (device_shared.h, kFilmChannel*), pixel by
  // pixel, filmChannelCounters of them each, counterWords() words each;
  // empty when not held. Bins: [pixel][bin]. Exact colour: the sums of
  // every counted beam's own x̄, ȳ, z̄ (times its weight ratio) in
  // colourUnitsPerCmf units. Squared weights (fractional weights): the sum
  // of squared weight ratios in the bins' units, for the error estimate.
  std::array<std::vector<uint64_t>, device::kFilmChannelCount> channels;
  uint64_t countedBeams = 0;  // beams counted (each added to one bin)

  SpectralHistogram() = default;
  SpectralHistogram(uint32_t px, uint32_t py, uint32_t nbins, bool exactColour = false, uint64_t units = 1)
      : pixelsX(px), pixelsY(py), bins(nbins), unitsPerBeam(units) {
    const uint32_t held = device::filmChannelSetOf(exactColour, units != 1);
    for (uint32_t c = 0; c < device::kFilmChannelCount; ++c)
      if (device::filmStoresChannel(held, c))
        channel(c).assign(size_t(px) * py * device::filmChannelCounters(c, nbins) * device::filmCounterWords(held), 0);
  }

  std::vector<uint64_t>& channel(uint32_t c) { return channels.at(c); }
  const std::vector<uint64_t>& channel(uint32_t c) const { return channels.at(c); }
  std::vector<uint64_t>& counts() { return channels[device::kFilmChannelBins]; }
  const std::vector<uint64_t>& counts() const { return channels[device::kFilmChannelBins]; }
  std::vector<uint64_t>& colourSums() { return channels[device::kFilmChannelColour]; }
  const std::vector<uint64_t>& colourSums() const { return channels[device::kFilmChannelColour]; }
  std::vector<uint64_t>& squaredWeightSums() { return channels[device::kFilmChannelSquaredWeight]; }
  const std::vector<uint64_t>& squaredWeightSums() const { return channels[device::kFilmChannelSquaredWeight]; }
  // The channels held (bit c for channel c).
  uint32_t channelSet() const { return device::filmChannelSetOf(hasExactColour(), isWeighted()); }

  bool hasExactColour() const { return !colourSums().empty(); }
  bool isWeighted() const { return unitsPerBeam != 1; }
  bool sameShape(const SpectralHistogram& o) const {
    return o.pixelsX == pixelsX && o.pixelsY == pixelsY && o.bins == bins && o.channelSet() == channelSet() &&
           o.unitsPerBeam == unitsPerBeam;
  }

  uint32_t counterWords() const { return isWeighted() ? 2 : 1; }
  // Counter i of channel c (pixel by pixel, as the channel holds them).
  device::WideCount counter(uint32_t c, size_t i) const {
    const std::vector<uint64_t>& words = channel(c);
    return isWeighted() ? device::WideCount{words[2 * i], words[2 * i + 1]} : device::WideCount{words[i], 0};
  }
  device::WideCount count(uint32_t pixel, uint32_t bin) const {
    return counter(device::kFilmChannelBins, size_t(pixel) * bins + bin);
  }
  // A plain film's hit count (one word per counter).
  uint64_t& at(uint32_t pixel, uint32_t bin) { return counts()[size_t(pixel) * bins + bin]; }
  uint64_t at(uint32_t pixel, uint32_t bin) const { return counts()[size_t(pixel) * bins + bin]; }
  // The sum of every bin counter, in counts (exact below 2^53).
  double total() const {
    double sum = 0;
    for (size_t i = 0; i < counts().size() / counterWords(); ++i) sum += realOf(counter(device::kFilmChannelBins, i));
    return sum;
  }
  // A plain film's hits: its bin counters' exact sum.
  uint64_t plainHits() const {
    uint64_t sum = 0;
    for (uint64_t c : counts()) sum += c;
    return sum;
  }
  // Adds another histogram of the same shape (a render over other beams).
  // Throws CounterOverflow when a sum would overflow; this histogram is
  // then partly added, so merge into a copy that can be dropped.
  void merge(const SpectralHistogram& other);
};

}  // namespace spectrace
