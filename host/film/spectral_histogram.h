#pragma once
// Per-pixel spectral histogram: exact 64-bit counts, [pixel][bin], pixels
// row-major from the top-left of the upright image. Integer counts make sums
// order-independent and bit-reproducible, so partial renders merge exactly.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "device_shared.h"

namespace spectrace {

// A channel's name in state files and messages.
inline const char* filmChannelName(uint32_t c) {
  return c < device::kFilmChannelCount ? device::kFilmChannelNames[c] : "?";
}

struct SpectralHistogram {
  uint32_t pixelsX = 0, pixelsY = 0, bins = 0;
  // What one full-weight beam adds to its bin: 1 (plain hit counts) or, when
  // aimed beams carry fractional weights, kWeightUnitsFractional.
  uint64_t unitsPerBeam = 1;
  // Each channel's counters (device_shared.h, kFilmChannel*), pixel by
  // pixel, filmChannelCounters of them each; empty when not held. Bins:
  // [pixel][bin]. Exact colour: the sums of every counted beam's own
  // x̄, ȳ, z̄ (times its weight ratio) in colour fixed point
  // (kColourFixedPointScale units). Squared weights (fractional weights):
  // the sum of squared weight ratios in the bins' units, for the error
  // estimate.
  std::array<std::vector<uint64_t>, device::kFilmChannelCount> channels;
  uint64_t countedBeams = 0;  // beams counted (each added to one bin)

  SpectralHistogram() = default;
  SpectralHistogram(uint32_t px, uint32_t py, uint32_t nbins, bool exactColour = false, uint64_t units = 1)
      : pixelsX(px), pixelsY(py), bins(nbins), unitsPerBeam(units) {
    const uint32_t held = device::filmChannelSetOf(exactColour, units != 1);
    for (uint32_t c = 0; c < device::kFilmChannelCount; ++c)
      if (device::filmStoresChannel(held, c)) channel(c).assign(size_t(px) * py * device::filmChannelCounters(c, nbins), 0);
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

  uint64_t& at(uint32_t pixel, uint32_t bin) { return counts()[size_t(pixel) * bins + bin]; }
  uint64_t at(uint32_t pixel, uint32_t bin) const { return counts()[size_t(pixel) * bins + bin]; }
  uint64_t total() const {
    uint64_t sum = 0;
    for (uint64_t c : counts()) sum += c;
    return sum;
  }
  // Adds another histogram of the same shape (a render over other beams).
  void merge(const SpectralHistogram& other) {
    if (!sameShape(other)) throw std::invalid_argument("cannot merge histograms of different shapes");
    for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) {  // every channel merges by exact addition
      std::vector<uint64_t>& mine = channel(c);
      const std::vector<uint64_t>& theirs = other.channel(c);
      for (size_t i = 0; i < mine.size(); ++i) mine[i] += theirs[i];
    }
    countedBeams += other.countedBeams;
  }
};

}  // namespace spectrace
