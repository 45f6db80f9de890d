// One beam, from its index to the film: emit (emit.h, lights/), transport
// (transport.h), sensor (sensor.h). Shared by the trace shader and the CPU
// reference; the includer provides what kernel_interface.h lists.
#ifndef SPECTRACE_TRACE_H
#define SPECTRACE_TRACE_H

#include "kernel_features.h"
#include "beam_math.h"
#include "emit.h"
#include "transport.h"
#include "sensor.h"

// Returns whether beam `beamIndex` reaches the camera with weight, and
// where: the pixel (column, row) and stored wavelength bin, with its weight ratio (> 0),
// its wavelength and a spare uniform (for rounding). Every random number
// comes from (seed, beamIndex, block), so the result is independent of
// batching, threads and device.
//
// The wavelength is drawn last, and only for a beam that reaches the
// camera: nothing between the light and the sensor depends on it yet
// (transport.h), and most beams miss. Valid while transport is independent
// of wavelength; a dispersive medium must draw it before transportBeam.
// Lazy drawing changes no beam: the spectral block's words are the same
// whenever they are drawn.
FN bool traceBeam(uint64_t beamIndex, OUT(uvec2) cell, OUT(uint) bin, OUT(float) lambda, OUT(float) spareUniform,
                  OUT(float) ratio) {
  uvec4 geometry = philox4x32(constants.seed, beamIndex, kRngBlockGeometry);
  LightRecord light = readLight(chooseLight(constants.seed, beamIndex));
  vec3 origin;
  vec3 direction;
  ratio = emitLightBeam(light, uniformFromWord(geometry.x), uniformFromWord(geometry.y),
                        uniformFromWord(geometry.z), uniformFromWord(geometry.w), origin, direction);
  bool travelling = transportBeam(beamIndex, origin, direction, ratio);
  bool hit = travelling && hitSensor(origin, direction, constants.sensorHalfSize, constants.pixelsPerMetre,
                                     constants.pixelsX, constants.pixelsY, constants.apertureDistance,
                                     constants.apertureRadiusSq, cell) && ratio > 0.0f;
  lambda = 0.0f;
  spareUniform = 0.0f;
  bin = 0u;
  if (hit) {
    uvec4 spectral = philox4x32(constants.seed, beamIndex, kRngBlockSpectral);
    lambda = drawWavelength(light, joinWords(spectral.x, spectral.y), uniformFromWord(spectral.z));
    spareUniform = uniformFromWord(spectral.w);
    // The bin of the full spectrum, then its place among the stored bins
    // (the host stores every bin a light can reach, so the clamp never acts).
    uint fullBin = binOfWavelength(lambda, constants.lambdaMin, constants.binsPerNm, constants.totalBins);
    bin = min(max(fullBin, constants.binOffset) - constants.binOffset, constants.bins - 1u);
  }
  return hit;
}

// Traces beam `beamIndex` and, when it reaches the camera, counts it into
// the film. Returns whether it was counted.
FN bool traceAndCountBeam(uint64_t beamIndex) {
  uvec2 cell;
  uint bin;
  float lambda;
  float spareUniform;
  float ratio;
  bool hit = traceBeam(beamIndex, cell, bin, lambda, spareUniform, ratio);
  return hit && countBeam(cell, bin, lambda, ratio, spareUniform);
}

#endif  // SPECTRACE_TRACE_H
