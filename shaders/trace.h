// One beam, from its index to the film: emit (emit.h, lights/), transport
// (transport.h), camera and sensor (camera.h, cameras/, sensor.h). Shared by the trace shader and the CPU
// reference; the includer provides what kernel_interface.h lists.
#ifndef SPECTRACE_TRACE_H
#define SPECTRACE_TRACE_H

#include "kernel_features.h"
#include "beam_math.h"
#include "scene_data.h"
#include "emit.h"
#include "camera.h"
#include "sensor.h"
#include "objects.h"
#include "transport.h"

// Traces beam `beamIndex` and notes what it put on the film in `tally`:
// counts it (or, in record mode, only notes it). Returns whether it made
// any count. Every random number comes from (seed, beamIndex, block), so the
// result is independent of batching, threads and device.
//
// Without objects the wavelength is drawn last, and only for a beam that
// reaches the camera: nothing between the light and the sensor depends on
// it, and most beams miss. With objects, materials depend on it, so it is
// drawn before transport. Lazy drawing changes no beam: the spectral
// block's words are the same whenever they are drawn.
FN bool traceBeam(uint64_t beamIndex, INOUT(BeamTally) tally) {
  uvec4 geometry = philox4x32(constants.seed, beamIndex, kRngBlockGeometry);
  LightRecord light = readLight(chooseLight(constants.seed, beamIndex));
  vec3 origin;
  vec3 direction;
  float ratio = emitLightBeam(light, uniformFromWord(geometry.x), uniformFromWord(geometry.y),
                              uniformFromWord(geometry.z), uniformFromWord(geometry.w), origin, direction);
  if (SPECTRACE_OBJECTS) {
    uvec4 spectral = philox4x32(constants.seed, beamIndex, kRngBlockSpectral);
    float lambda = drawWavelength(light, joinWords(spectral.x, spectral.y), uniformFromWord(spectral.z));
    transportBeam(beamIndex, origin, direction, ratio, lambda, uniformFromWord(spectral.w), tally);
  } else {
    uvec2 cell;
    bool hit = hitSensor(origin, direction, cell) && ratio > 0.0f;
    if (hit) {
      uvec4 spectral = philox4x32(constants.seed, beamIndex, kRngBlockSpectral);
      float lambda = drawWavelength(light, joinWords(spectral.x, spectral.y), uniformFromWord(spectral.z));
      contribute(tally, cell, storedBinOf(lambda), lambda, ratio, uniformFromWord(spectral.w));
    }
  }
  return tally.contributions > 0u;
}

// Traces beam `beamIndex` and counts what reaches the camera into the
// film. Returns whether it was counted.
FN bool traceAndCountBeam(uint64_t beamIndex) {
  BeamTally tally = emptyTally();
  return traceBeam(beamIndex, tally);
}

#endif  // SPECTRACE_TRACE_H
