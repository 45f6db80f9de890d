// One beam from index to (pixel, bin), shared by the trace shader and the
// CPU reference (see beam_math.h). The includer also provides
//   uvec4 philox4x32(uint64_t seed, uint64_t index, uint block)
//   LightRecord readLight(uint i); SpectralInterval readInterval(uint i)
// and `constants` (TraceConstants).
#ifndef SPECTRACE_BEAM_TRACE_H
#define SPECTRACE_BEAM_TRACE_H

#ifndef SPECTRACE_SELECT_LIGHT
#define SPECTRACE_SELECT_LIGHT (constants.lightCount > 1u)
#endif

SPECTRACE_CDF_SEARCH(searchLight, readLightCdf)
SPECTRACE_CDF_SEARCH(searchSpectralInterval, readSpectralCdf)

// A wavelength from one light's spectral table: the interval by an exact
// integer CDF over a 64-bit uniform, the position inside it in closed form.
FN float drawWavelength(uint spectralFirst, uint spectralCount, uint64_t intervalUniform, float positionUniform) {
  uint intervalIndex = searchSpectralInterval(spectralFirst, spectralCount, intervalUniform);
  SpectralInterval interval = readInterval(intervalIndex);
  return wavelengthInInterval(interval.lambda0, interval.width, interval.slope, positionUniform);
}

// The observer's CMF at a wavelength, linear between the table's nodes and
// zero outside (the includer provides vec3 readCmf(uint node)).
FN vec3 cmfAtWavelength(float lambda) {
  PRECISE float x = (lambda - constants.cmfLambdaMin) * constants.cmfNodesPerNm;
  vec3 result = vec3(0.0f, 0.0f, 0.0f);
  if (x >= 0.0f && x <= float(constants.cmfCount - 1u)) {
    uint node = min(uint(x), constants.cmfCount - 2u);
    PRECISE float t = x - float(node);
    vec3 a = readCmf(node);
    vec3 b = readCmf(node + 1u);
    PRECISE vec3 c = a + (b - a) * t;
    result = c;
  }
  return result;
}

// A CMF value in colour fixed point, rounded up with probability equal to
// its fraction, so the sum is unbiased (to 2^-24 of a quantum, the
// resolution of `u`, a uniform in [0, 1)). Scaling by 2^20, floor and the
// subtraction are all exact in float.
FN uint64_t colourFixedPoint(float value, float u) {
  PRECISE float scaled = value * kColourFixedPointScale;
  PRECISE float whole = floor(scaled);
  PRECISE float fraction = scaled - whole;
  return uint64_t(whole) + (u < fraction ? 1ul : 0ul);
}

// Returns whether beam `beamIndex` reaches the sensor, and where: the pixel
// and wavelength bin. Every random number comes from (seed, beamIndex,
// block), so the result is independent of batching, threads and device.
// Also returns the beam's wavelength and a spare uniform (for rounding).
FN bool traceBeam(uint64_t beamIndex, OUT(uint) pixel, OUT(uint) bin, OUT(float) lambda, OUT(float) spareUniform) {
  uvec4 spectral = philox4x32(constants.seed, beamIndex, kRngBlockSpectral);
  uvec4 geometry = philox4x32(constants.seed, beamIndex, kRngBlockGeometry);

  // Light in proportion to its traced power, then interval in proportion to
  // its power: both exact integer CDFs over 64-bit uniforms.
  uint lightIndex = 0u;
  if (SPECTRACE_SELECT_LIGHT) {
    uvec4 select = philox4x32(constants.seed, beamIndex, kRngBlockLight);
    lightIndex = searchLight(0u, constants.lightCount, joinWords(select.x, select.y));
  }
  LightRecord light = readLight(lightIndex);
  lambda = drawWavelength(light.spectralFirst, light.spectralCount, joinWords(spectral.x, spectral.y),
                                uniformFromWord(spectral.z));
  spareUniform = uniformFromWord(geometry.w);
  // The bin of the full spectrum, then its place among the stored bins (the
  // host stores every bin a light can reach, so the clamp never acts).
  uint fullBin = binOfWavelength(lambda, constants.lambdaMin, constants.binsPerNm, constants.totalBins);
  bin = min(max(fullBin, constants.binOffset) - constants.binOffset, constants.bins - 1u);

  vec3 origin;
  vec3 direction;
  emitBeam(light.type, light.position, light.axis, light.tangent, light.bitangent, light.param0,
           light.param1, uniformFromWord(spectral.w), uniformFromWord(geometry.x),
           uniformFromWord(geometry.y), uniformFromWord(geometry.z), origin, direction);
  return hitSensor(origin, direction, constants.sensorHalfSize, constants.pixelsPerMetre,
                   constants.pixelsX, constants.pixelsY, constants.apertureDistance,
                   constants.apertureRadiusSq, pixel);
}

#endif  // SPECTRACE_BEAM_TRACE_H
