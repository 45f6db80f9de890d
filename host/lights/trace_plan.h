#pragma once
// Everything a trace needs, derived from a scene in double precision on the
// host: the device tables (light records in the camera frame, spectral
// intervals, integer CDFs) and the physical scale of one count.
#include <cstdint>
#include <string>
#include <vector>

#include "cpu/spectral_histogram.h"
#include "device_shared.h"
#include "scene/scene.h"

namespace spectrace {

struct LightSummary {
  std::string label;       // e.g. "/lights/2 (disk, D65)"
  double powerW = 0.0;     // as given
  double inRangeShare = 0.0;  // share of the emission inside the spectrum range
  double tracedPowerW = 0.0;  // powerW * inRangeShare
  bool traced = false;        // false: never sampled
  bool aimed = false;         // beams drawn only towards the camera
  // Aimed: the largest weight a beam can carry, about the share of the
  // light's emission that is sampled (1 when not aimed).
  double largestWeight = 1.0;
  std::string notTracedBecause;  // why, when not traced
};

struct TracePlan {
  device::TraceConstants constants{};
  std::vector<device::LightRecord> lights;
  std::vector<device::SpectralInterval> intervals;
  std::vector<glm::vec3> cmfTable;      // the observer's CMF nodes, for exact colour
  std::vector<LightSummary> summaries;  // one per scene light, in scene order
  double tracedPowerW = 0.0;            // sum over traced lights
  // Sum over traced lights of power x largest weight: the power a
  // full-weight beam stands for, times the beam count (= tracedPowerW
  // without aiming).
  double sampledPowerW = 0.0;
  double pixelAreaM2 = 0.0;
  double lambdaMinNm = 0.0, lambdaMaxNm = 0.0;
  uint32_t pixelsX = 0, pixelsY = 0, bins = 0;  // bins of the full spectrum (host histograms, output)
  // The bins the device stores: [firstStoredBin, firstStoredBin + storedBins).
  uint32_t firstStoredBin() const { return constants.binOffset; }
  uint32_t storedBins() const { return constants.bins; }

  uint64_t pixelCount() const { return uint64_t(pixelsX) * pixelsY; }
  // The pixels the device stores: a window of the sensor (TraceConstants).
  uint64_t storedPixelCount() const { return uint64_t(constants.windowWidth) * constants.windowHeight; }
  uint64_t fullPixelOfStored(uint64_t stored) const {
    const uint64_t row = stored / constants.windowWidth, column = stored % constants.windowWidth;
    return (row + constants.windowY0) * pixelsX + column + constants.windowX0;
  }
  // Whether the device stores pixel `pixel` (row-major over the sensor).
  bool storesPixel(uint64_t pixel) const {
    const uint64_t row = pixel / pixelsX, column = pixel % pixelsX;
    return row >= constants.windowY0 && row < uint64_t(constants.windowY0) + constants.windowHeight &&
           column >= constants.windowX0 && column < uint64_t(constants.windowX0) + constants.windowWidth;
  }
  bool weighted() const { return constants.weightUnits != 1; }
  // An all-zero histogram of this plan's shape (all bins of the spectrum).
  SpectralHistogram emptyHistogram() const {
    return SpectralHistogram(pixelsX, pixelsY, bins, exactColour(), constants.weightUnits);
  }
  bool hasShapeOf(const SpectralHistogram& h) const {
    return h.pixelsX == pixelsX && h.pixelsY == pixelsY && h.bins == bins && h.hasExactColour() == exactColour() &&
           h.unitsPerBeam == constants.weightUnits;
  }
  bool exactColour() const { return constants.exactColour != 0; }
  uint32_t countersPerPixel() const { return constants.countersPerPixel; }
  // W/m^2 per bin carried by one count when `beams` beams were traced: a
  // full-weight beam carries sampledPowerW * exposure / beams joules, spread
  // over one pixel's area and the exposure time (which cancels), and adds
  // weightUnits counts.
  double irradiancePerCount(uint64_t beams) const {
    return sampledPowerW / (double(beams) * pixelAreaM2 * double(constants.weightUnits));
  }
};

struct TracePlanOptions {
  // Accumulate each counted beam's own CMF values per pixel (exact colour
  // whatever the bin count); otherwise colour comes from bin-averaged CMFs.
  bool exactColour = true;
  // Never sample lights that provably cannot reach the sensor (behind it or
  // the aperture, facing away, a collimated beam that misses). Off: trace
  // them anyway (the unskipped reference path).
  bool skipUnreachableLights = true;
  // Store only the wavelength bins the traced lights can reach (a 532 nm
  // laser needs one); off: store the whole spectrum range.
  bool trimSpectrum = true;
  // Store only the pixels beams can reach (a rectangle: the image of the
  // lights through a pinhole, a laser's footprint); off: the whole sensor.
  bool trimPixels = true;
  // Draw beams only towards the camera (the pinhole, or the bare sensor),
  // weighted so the estimate is unbiased; off: analog emission (the
  // reference path).
  bool aim = true;
};

// Throws SceneError (with the scene file's name) for scenes that cannot be
// traced, e.g. when no light has power inside the spectrum range.
TracePlan buildTracePlan(const Scene& scene, uint64_t seed, const TracePlanOptions& options = {});

}  // namespace spectrace
