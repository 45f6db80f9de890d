#pragma once
// Everything a trace needs, derived from a scene in double precision on the
// host: the device tables (light records in the camera frame, spectral
// intervals, integer CDFs) and the physical scale of one count.
#include <cstdint>
#include <string>
#include <vector>

#include "device_shared.h"
#include "scene/scene.h"

namespace spectrace {

struct LightSummary {
  std::string label;       // e.g. "/lights/2 (disk, D65)"
  double powerW = 0.0;     // as given
  double inRangeShare = 0.0;  // share of the emission inside the spectrum range
  double tracedPowerW = 0.0;  // powerW * inRangeShare
  bool traced = false;        // false: never sampled
  std::string notTracedBecause;  // why, when not traced
};

struct TracePlan {
  device::TraceConstants constants{};
  std::vector<device::LightRecord> lights;
  std::vector<device::SpectralInterval> intervals;
  std::vector<glm::vec3> cmfTable;      // the observer's CMF nodes, for exact colour
  std::vector<LightSummary> summaries;  // one per scene light, in scene order
  double tracedPowerW = 0.0;            // sum over traced lights
  double pixelAreaM2 = 0.0;
  double lambdaMinNm = 0.0, lambdaMaxNm = 0.0;
  uint32_t pixelsX = 0, pixelsY = 0, bins = 0;  // bins of the full spectrum (host histograms, output)
  // The bins the device stores: [firstStoredBin, firstStoredBin + storedBins).
  uint32_t firstStoredBin() const { return constants.binOffset; }
  uint32_t storedBins() const { return constants.bins; }

  uint64_t pixelCount() const { return uint64_t(pixelsX) * pixelsY; }
  bool exactColour() const { return constants.exactColour != 0; }
  uint32_t countersPerPixel() const { return constants.countersPerPixel; }
  // W/m^2 per bin carried by one count when `beams` beams were traced: each
  // beam carries tracedPowerW * exposure / beams joules, spread over one
  // pixel's area and the exposure time (which cancels).
  double irradiancePerCount(uint64_t beams) const { return tracedPowerW / (double(beams) * pixelAreaM2); }
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
};

// Throws SceneError (with the scene file's name) for scenes that cannot be
// traced, e.g. when no light has power inside the spectrum range.
TracePlan buildTracePlan(const Scene& scene, uint64_t seed, const TracePlanOptions& options = {});

}  // namespace spectrace
