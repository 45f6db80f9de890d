// One beam, from its index to the film: emit (emit.h, lights/), transport
// (transport.h), camera and sensor (camera.h, cameras/, sensor.h); and the
// camera path of the same index (camera_path.h). Shared by the trace shader and the CPU
// reference; the includer provides what kernel_interface.h lists.
#ifndef SPECTRACE_TRACE_H
#define SPECTRACE_TRACE_H

#include "kernel_features.h"
#include "beam_math.h"
#include "scene_data.h"
#include "emit.h"
#include "light_arrival.h"
#include "camera.h"
#include "sensor.h"
#include "wavelengths.h"
#include "objects.h"
#include "transport.h"
#ifdef SPECTRACE_WITH_CAMERA_PATHS
#include "camera_path.h"
#endif

// Light path `beamIndex` (a beam): counted into the film, or noted in
// `tally`. Every random number comes from (seed, beamIndex, block), so the
// result is independent of batching, threads and device.
//
// A beam carries constants.wavelengthsPerPath wavelengths (wavelengths.h),
// each counted with its share of the beam's weight.
//
// Without objects the wavelengths are drawn last, and only for a beam that
// reaches the camera: nothing between the light and the sensor depends on
// it, and most beams miss. With objects, materials depend on it, so it is
// drawn before transport, as it is before a lens system's glass. Lazy
// drawing changes no beam: the spectral block's words are the same
// whenever they are drawn.
//
// With camera paths, the paths they count are left to them (camera_path.h):
// every path from an emitter with an area, and, from the other lights but
// lasers, every path whose first surface is diffuse.
FN void traceLightPath(uint64_t beamIndex, INOUT(BeamTally) tally) {
  LightRecord light = readLight(chooseLight(constants.seed, beamIndex, kRngBlockLight));
  bool cameraPaths = SPECTRACE_CAMERA_PATHS;
  if (cameraPaths && lightSeenDirectly(light)) return;
  uvec4 geometry = philox4x32(constants.seed, beamIndex, kRngBlockGeometry);
  vec3 origin;
  vec3 direction;
  float ratio = emitLightBeam(light, geometry, beamIndex, origin, direction);
  if (SPECTRACE_OBJECTS) {
    uvec4 spectral = philox4x32(constants.seed, beamIndex, kRngBlockSpectral);
    PathWavelengths w = drawPathWavelengths(light, joinWords(spectral.x, spectral.y), uniformFromWord(spectral.z),
                                            constants.wavelengthsPerPath);
    bool diffuseFirstIsCameras = cameraPaths && lightLightsPoints(light);
    transportBeam(beamIndex, origin, direction, ratio, w, uniformFromWord(spectral.w), diffuseFirstIsCameras, tally);
  } else if (SPECTRACE_CAMERA_TYPE == kCameraLensSystem) {
    // The lens bends each wavelength its own way: drawn before the sensor.
    uvec4 spectral = philox4x32(constants.seed, beamIndex, kRngBlockSpectral);
    PathWavelengths w = drawPathWavelengths(light, joinWords(spectral.x, spectral.y), uniformFromWord(spectral.z),
                                            constants.wavelengthsPerPath);
    uvec2 cell;
    float transmission;
    if (hitSensor(origin, direction, w.lambda[0], cell, transmission) && ratio > 0.0f)
      countAtCamera(beamIndex, cell, transmission, w, ratio, uniformFromWord(spectral.w), tally);
  } else {
    uvec2 cell;
    float transmission;
    bool hit = hitSensor(origin, direction, 0.0f, cell, transmission) && ratio > 0.0f;
    if (hit) {
      uvec4 spectral = philox4x32(constants.seed, beamIndex, kRngBlockSpectral);
      PathWavelengths w = drawPathWavelengths(light, joinWords(spectral.x, spectral.y), uniformFromWord(spectral.z),
                                              constants.wavelengthsPerPath);
      contributeCounts(tally, cell, w, sharesTimes(w, ratio), uniformFromWord(spectral.w));
    }
  }
}

// Path index `pathIndex` through the render's estimators (device_shared.h,
// kEstimator*): its light path, then its camera path. Notes what they put on
// the film in `tally`: counts it (or, in record mode, only notes it).
// Returns whether they made any count.
FN bool traceBeam(uint64_t pathIndex, INOUT(BeamTally) tally) {
  if (SPECTRACE_LIGHT_PATHS) traceLightPath(pathIndex, tally);
#ifdef SPECTRACE_WITH_CAMERA_PATHS
  if (SPECTRACE_CAMERA_PATHS) traceCameraPath(pathIndex, tally);
#endif
  return tally.contributions > 0u;
}

// Traces beam `beamIndex` and counts what reaches the camera into the
// film. Returns whether it was counted.
FN bool traceAndCountBeam(uint64_t beamIndex) {
  BeamTally tally = emptyTally();
  return traceBeam(beamIndex, tally);
}

#endif  // SPECTRACE_TRACE_H
