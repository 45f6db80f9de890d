#pragma once
// Per-pixel spectral histogram: exact 64-bit counts, [pixel][bin], pixels
// row-major from the top-left of the upright image. Integer counts make sums
// order-independent and bit-reproducible, so partial renders merge exactly.
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace spectrace {

struct SpectralHistogram {
  uint32_t pixelsX = 0, pixelsY = 0, bins = 0;
  // What one full-weight beam adds to its bin: 1 (plain hit counts) or, when
  // aimed beams carry fractional weights, kWeightUnitsFractional.
  uint64_t unitsPerBeam = 1;
  std::vector<uint64_t> counts;
  // With exact colour: per pixel, the sums of every counted beam's own
  // x̄, ȳ, z̄ (times its weight ratio) in colour fixed point
  // (kColourFixedPointScale units); else empty.
  std::vector<uint64_t> colourSums;
  // With fractional weights: per pixel, the sum of squared weight ratios in
  // the same units as counts (for the error estimate); else empty.
  std::vector<uint64_t> squaredWeightSums;
  uint64_t countedBeams = 0;  // beams counted (each added to one bin)

  SpectralHistogram() = default;
  SpectralHistogram(uint32_t px, uint32_t py, uint32_t nbins, bool exactColour = false, uint64_t units = 1)
      : pixelsX(px), pixelsY(py), bins(nbins), unitsPerBeam(units), counts(size_t(px) * py * nbins, 0),
        colourSums(exactColour ? size_t(px) * py * 3 : 0, 0), squaredWeightSums(units != 1 ? size_t(px) * py : 0, 0) {}

  bool hasExactColour() const { return !colourSums.empty(); }
  bool isWeighted() const { return unitsPerBeam != 1; }
  bool sameShape(const SpectralHistogram& o) const {
    return o.pixelsX == pixelsX && o.pixelsY == pixelsY && o.bins == bins && o.colourSums.size() == colourSums.size() &&
           o.unitsPerBeam == unitsPerBeam;
  }

  uint64_t& at(uint32_t pixel, uint32_t bin) { return counts[size_t(pixel) * bins + bin]; }
  uint64_t at(uint32_t pixel, uint32_t bin) const { return counts[size_t(pixel) * bins + bin]; }
  uint64_t total() const {
    uint64_t sum = 0;
    for (uint64_t c : counts) sum += c;
    return sum;
  }
  // Adds another histogram of the same shape (a render over other beams).
  void merge(const SpectralHistogram& other) {
    if (!sameShape(other)) throw std::invalid_argument("cannot merge histograms of different shapes");
    for (size_t i = 0; i < counts.size(); ++i) counts[i] += other.counts[i];
    for (size_t i = 0; i < colourSums.size(); ++i) colourSums[i] += other.colourSums[i];
    for (size_t i = 0; i < squaredWeightSums.size(); ++i) squaredWeightSums[i] += other.squaredWeightSums[i];
    countedBeams += other.countedBeams;
  }
};

}  // namespace spectrace
