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

// `scaled` rounded down or up, up with probability equal to its fraction,
// so the sum is unbiased (to 2^-24 of a unit, the resolution of `u`, a
// uniform in [0, 1)). floor and the subtraction are exact in float.
FN uint64_t roundStochastic(float scaled, float u) {
  PRECISE float whole = floor(scaled);
  PRECISE float fraction = scaled - whole;
  return uint64_t(whole) + (u < fraction ? 1ul : 0ul);
}

// A CMF value (times the beam's weight ratio) in colour fixed point. The
// scaling by 2^20 is exact.
FN uint64_t colourFixedPoint(float value, float u) {
  PRECISE float scaled = value * kColourFixedPointScale;
  return roundStochastic(scaled, u);
}

// What a counted beam of weight ratio `ratio` adds to its bin, and
// ratio^2 in the same units to its pixel's squared-weight counter, in units
// of 1 / weightUnits of a full-weight beam (device_shared.h). With
// weightUnits == 1 every ratio is 1.
FN uint64_t weightUnitsOf(float ratio, float u) {
  PRECISE float scaled = ratio * float(constants.weightUnits);  // exact: a power of two
  return constants.weightUnits == 1u ? 1ul : roundStochastic(scaled, u);
}
FN uint64_t squaredWeightUnitsOf(float ratio, float u) {
  PRECISE float scaled = (ratio * ratio) * float(constants.weightUnits);
  return roundStochastic(scaled, u);
}

// The seed's getNextBeam(), aimed where the light allows: origin and
// direction of a beam from `light` from four uniforms, and its weight ratio
// (emission density / sampling density, over the light's largest such value;
// 0: the beam carries nothing). See lights/trace_plan.cpp for each case.
FN float emitLightBeam(LightRecord light, float ou, float ov, float du, float dv, OUT(vec3) origin,
                       OUT(vec3) direction) {
  bool aimed = SPECTRACE_AIM && light.aimed != 0u;
  bool pointLike = light.type == kLightPoint || light.type == kLightSpot;
  float ratio = 1.0f;
  if (aimed && SPECTRACE_LIGHT_ENABLED(kLightLaser) && light.type == kLightLaser) {
    // Origins uniform over the disk whose collimated beams can reach the
    // target; those outside the laser's own cross-section carry nothing.
    vec2 p = sampleDisk(ou, ov, light.aimSpread);
    PRECISE vec2 q = vec2(light.aimAxis.x + p.x, light.aimAxis.y + p.y);
    PRECISE float q2 = q.x * q.x + q.y * q.y;
    PRECISE vec3 o = light.position + light.tangent * q.x + light.bitangent * q.y;
    origin = o;
    direction = light.axis;
    if (!(q2 <= light.aimAccept)) ratio = 0.0f;
  } else {
    origin = emitOrigin(light.type, light.position, light.tangent, light.bitangent, light.param0, light.param1, ou, ov);
    if (aimed && pointLike) {
      // Uniform in the cone holding the target; spot beams outside the
      // spot's own cone carry nothing.
      direction = toFrame(sampleCone(du, dv, light.aimSpread), light.aimTangent, light.aimBitangent, light.aimAxis);
      if (SPECTRACE_LIGHT_ENABLED(kLightSpot) && light.type == kLightSpot) {
        vec3 off = cross3(direction, light.axis);
        if (!(dot3(direction, light.axis) > 0.0f) || !(dot3(off, off) <= light.aimAccept)) ratio = 0.0f;
      }
    } else if (aimed) {
      // Disk or rectangle: uniform in the cone from this origin that holds
      // the target sphere, when that cone is narrower than a hemisphere's
      // worth of cosine-weighted emission (2h < 1); ratio cos(theta) 2h, the
      // density cos(theta)/pi over 1/(2 pi h), scaled by aimWeightScale.
      PRECISE vec3 toCentre = constants.aimCentre - origin;
      PRECISE float distance = sqrt(dot3(toCentre, toCentre));
      PRECISE float sinHalf = constants.aimRadius / distance + SPECTRACE_AIM_SLACK;
      if (sinHalf * sinHalf < 0.75f) {
        float h = oneMinusCosFromSin(sinHalf);
        PRECISE vec3 coneAxis = toCentre / distance;
        vec3 t;
        vec3 b;
        frameAround(coneAxis, t, b);
        direction = toFrame(sampleCone(du, dv, h), t, b, coneAxis);
        PRECISE float cosTheta = dot3(direction, light.axis);
        PRECISE float weight = cosTheta * (2.0f * h) * light.aimWeightScale;
        ratio = cosTheta > 0.0f ? min(weight, 1.0f) : 0.0f;
      } else {
        direction = emitDirection(light.type, light.axis, light.tangent, light.bitangent, light.param0, du, dv);
        ratio = min(light.aimWeightScale, 1.0f);
      }
    } else {
      direction = emitDirection(light.type, light.axis, light.tangent, light.bitangent, light.param0, du, dv);
    }
  }
  return ratio;
}

// Returns whether beam `beamIndex` is counted, and where: the pixel and
// wavelength bin, with its weight ratio (> 0). Every random number comes
// from (seed, beamIndex, block), so the result is independent of batching,
// threads and device. Also returns the beam's wavelength and a spare
// uniform (for rounding).
FN bool traceBeam(uint64_t beamIndex, OUT(uint) pixel, OUT(uint) bin, OUT(float) lambda, OUT(float) spareUniform,
                  OUT(float) ratio) {
  uvec4 spectral = philox4x32(constants.seed, beamIndex, kRngBlockSpectral);
  uvec4 geometry = philox4x32(constants.seed, beamIndex, kRngBlockGeometry);

  // Light in proportion to its sampled power, then interval in proportion
  // to its power: both exact integer CDFs over 64-bit uniforms.
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
  ratio = emitLightBeam(light, uniformFromWord(spectral.w), uniformFromWord(geometry.x),
                        uniformFromWord(geometry.y), uniformFromWord(geometry.z), origin, direction);
  bool hit = hitSensor(origin, direction, constants.sensorHalfSize, constants.pixelsPerMetre,
                       constants.pixelsX, constants.pixelsY, constants.apertureDistance,
                       constants.apertureRadiusSq, pixel);
  return hit && ratio > 0.0f;
}

#endif  // SPECTRACE_BEAM_TRACE_H
