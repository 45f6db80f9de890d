#pragma once
// Everything a trace needs, derived from a scene in double precision on the
// host: the device tables (light records in the camera frame, spectral
// intervals, integer CDFs) and the physical scale of one count.
#include <cstdint>
#include <string>
#include <vector>

#include "film/film_layout.h"
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
  // Scene-wide kernel constants. Their film fields (window, stored bins,
  // countersPerPixel) mirror `film`; pixelsPerChunk is the backend's.
  device::TraceConstants constants{};
  std::vector<device::LightRecord> lights;
  std::vector<device::SpectralInterval> intervals;
  std::vector<glm::vec3> cmfTable;      // the observer's CMF nodes, for exact colour
  FilmLayout film;                      // what the device stores, and how
  std::vector<LightSummary> summaries;  // one per scene light, in scene order
  double tracedPowerW = 0.0;            // sum over traced lights
  // Sum over traced lights of power x largest weight: the power a
  // full-weight beam stands for, times the beam count (= tracedPowerW
  // without aiming).
  double sampledPowerW = 0.0;

  // W/m^2 per bin carried by one count when `beams` beams were traced: a
  // full-weight beam carries sampledPowerW * exposure / beams joules, spread
  // over one pixel's area and the exposure time (which cancels), and adds
  // weightUnits counts.
  double irradiancePerCount(uint64_t beams) const {
    return sampledPowerW / (double(beams) * film.pixelAreaM2 * double(film.weightUnits));
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
