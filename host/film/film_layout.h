#pragma once
// The film: what the camera records, defined once. The sensor's pixels and
// the spectrum's bins; the part of them the device stores (a window of
// pixels beams can reach, the bins lights can reach); and each stored
// pixel's counters, in the layout of shaders/device_shared.h
// (countersPerPixelOf). Host histograms (SpectralHistogram) always hold the
// whole sensor and spectrum; pack/unpack convert to and from the device's
// stored counters. Compare Mitsuba 3's Film and pbrt-v4's film.h.
#include <cstdint>
#include <span>
#include <vector>

#include "device_shared.h"
#include "film/spectral_histogram.h"

namespace spectrace {

// Where one channel's counters of a pixel are, on the device and on the
// host, in 64-bit words (filmCounterWords per counter): a stored pixel's
// words [deviceOffset, deviceOffset + counters) are the host histogram's
// [hostFirst, hostFirst + counters) of the pixel's hostCounters words (the
// bins: a trimmed spectrum stores some of them).
struct StoredChannel {
  uint32_t channel;  // device_shared.h, kFilmChannel*
  uint32_t deviceOffset, counters;
  uint32_t hostFirst, hostCounters;
};

// Columns [x0, x0 + width) and rows [y0, y0 + height) of the sensor.
struct PixelWindow {
  uint32_t x0 = 0, y0 = 0, width = 0, height = 0;
};

struct FilmLayout {
  uint32_t pixelsX = 0, pixelsY = 0;
  uint32_t bins = 0;  // bins of the full spectrum (host histograms, output)
  double lambdaMinNm = 0.0, lambdaMaxNm = 0.0;
  double pixelAreaM2 = 0.0;
  // What the device stores.
  PixelWindow window;
  uint32_t firstStoredBin = 0, storedBins = 0;
  bool exactColour = true;    // per-beam CMF sums per pixel
  bool colourFromBins = false;  // exact colour from bin counts instead (compile/shortcuts.h)
  uint64_t weightUnits = 1;   // what a full-weight beam adds to its bin (1 or kWeightUnitsFractional)

  bool weighted() const { return weightUnits != 1; }
  // The channels stored (bit c for channel c), and each with its place.
  uint32_t channelSet() const { return device::filmChannelSetOf(exactColour, weighted()); }
  std::vector<StoredChannel> channels() const;
  uint32_t countersPerPixel() const { return device::countersPerPixelOf(storedBins, channelSet()); }
  uint64_t pixelCount() const { return uint64_t(pixelsX) * pixelsY; }
  uint64_t storedPixelCount() const { return uint64_t(window.width) * window.height; }
  uint64_t storedCounterCount() const { return storedPixelCount() * countersPerPixel(); }
  // The sensor pixel (row-major) of stored pixel `stored` (row-major in the window).
  uint64_t fullPixelOfStored(uint64_t stored) const {
    const uint64_t row = stored / window.width, column = stored % window.width;
    return (row + window.y0) * pixelsX + column + window.x0;
  }
  bool storesPixel(uint64_t pixel) const {
    const uint64_t row = pixel / pixelsX, column = pixel % pixelsX;
    return row >= window.y0 && row < uint64_t(window.y0) + window.height && column >= window.x0 &&
           column < uint64_t(window.x0) + window.width;
  }
  // An all-zero host histogram of this film (every pixel and bin).
  SpectralHistogram emptyHistogram() const {
    return SpectralHistogram(pixelsX, pixelsY, bins, exactColour, weightUnits);
  }
  bool hasShapeOf(const SpectralHistogram& h) const {
    return h.pixelsX == pixelsX && h.pixelsY == pixelsY && h.bins == bins && h.hasExactColour() == exactColour &&
           h.unitsPerBeam == weightUnits;
  }
};

// Packs the stored part of `histogram` into device counters, pixels
// [firstPixel, firstPixel + out.size() / countersPerPixel) of the window.
// Throws std::invalid_argument when the histogram has counts the film does
// not store.
void packDeviceCounters(const SpectralHistogram& histogram, const FilmLayout& film, size_t firstPixel,
                        std::span<uint64_t> out);
// Unpacks device counters of stored pixels starting at firstPixel into `histogram`.
void unpackDeviceCounters(std::span<const uint64_t> counters, const FilmLayout& film, size_t firstPixel,
                          SpectralHistogram& histogram);

}  // namespace spectrace
