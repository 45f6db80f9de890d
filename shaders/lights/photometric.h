// Photometric light (kernel unit; host unit: host/lights/photometric_light.cpp):
// a luminaire's goniometric table (IES LM-63 or EULUMDAT), intensity
// bilinear in C and gamma, from `position`. The frame: `axis` is nadir
// (gamma = 0), `tangent` the C = 0 half-plane and `bitangent` C = 90
// degrees (the host's camera frame is left-handed, so compile_scene's
// cross(axis, tangent) is the image of the world's cross(C0, nadir)).
// The table's words are laid out as device_shared.h says
// (kPhotometricHeaderWords).
//
// Emission is exact: a patch by its flux through the alias table, then a
// direction inside it by rejection, proposing C and gamma uniformly and
// accepting with I(C, gamma) sin(gamma) / (the patch's envelope), so the
// accepted density is I sin(gamma) over the patch's flux, and over all
// patches I / (the table's flux), to float precision (the acceptance ratio
// as a float, truncated to 2^-32). The host sets the number of tries so that
// a beam runs out of them with probability below 2^-64 (then it carries
// nothing).
#ifndef SPECTRACE_LIGHTS_PHOTOMETRIC_H
#define SPECTRACE_LIGHTS_PHOTOMETRIC_H

struct PhotometricLayout {
  uint nC;
  uint nG;
  uint aliasBits;
  uint tries;
  uint cFirst;          // C angles, turns
  uint gFirst;          // gamma angles, turns
  uint intensityFirst;  // sr^-1, C major
  uint envelopeFirst;
  uint aliasFirst;
};

FN PhotometricLayout photometricTable(LightRecord light) {
  PhotometricLayout t;
  t.nC = readSceneWord(light.dataFirst);
  t.nG = readSceneWord(light.dataFirst + 1u);
  t.aliasBits = readSceneWord(light.dataFirst + 2u);
  t.tries = readSceneWord(light.dataFirst + 3u);
  t.cFirst = light.dataFirst + kPhotometricHeaderWords;
  t.gFirst = t.cFirst + t.nC;
  t.intensityFirst = t.gFirst + t.nG;
  t.envelopeFirst = t.intensityFirst + t.nC * t.nG;
  t.aliasFirst = t.envelopeFirst + (t.nC - 1u) * (t.nG - 1u);
  return t;
}

// Bilinear intensity in the patch (c, g) at fractions s along C and r along
// gamma; never below 0.
FN float photometricBilinear(PhotometricLayout t, uint c, uint g, float s, float r) {
  uint at = t.intensityFirst + c * t.nG + g;
  float i00 = readSceneFloat(at);
  float i01 = readSceneFloat(at + 1u);
  float i10 = readSceneFloat(at + t.nG);
  float i11 = readSceneFloat(at + t.nG + 1u);
  PRECISE float low = i00 + s * (i10 - i00);   // along C at gamma entry g
  PRECISE float high = i01 + s * (i11 - i01);  // and at g + 1
  PRECISE float value = low + r * (high - low);
  return max(value, 0.0f);
}

// Returns the weight ratio: 1, or 0 for the beam that ran out of tries.
FN float emitPhotometricBeam(LightRecord light, uvec4 geometry, uint64_t beamIndex, OUT(vec3) direction) {
  PhotometricLayout t = photometricTable(light);
  uint chosen = sceneAliasLookup(t.aliasFirst, t.aliasBits, joinWords(geometry.x, geometry.y));
  uint c = chosen / (t.nG - 1u);
  uint g = chosen - c * (t.nG - 1u);
  float c0 = readSceneFloat(t.cFirst + c);
  float c1 = readSceneFloat(t.cFirst + c + 1u);
  float g0 = readSceneFloat(t.gFirst + g);
  float g1 = readSceneFloat(t.gFirst + g + 1u);
  float envelope = readSceneFloat(t.envelopeFirst + chosen);
  direction = light.axis;
  for (uint i = 0u; i < t.tries; ++i) {
    uvec4 words = philox4x32(constants.seed, beamIndex, kRngBlockPhotometricTry + i);
    float s = uniformFromWord(words.x);
    float r = uniformFromWord(words.y);
    PRECISE float gTurns = g0 + r * (g1 - g0);
    vec2 gamma = cosSin2Pi(gTurns);
    PRECISE float density = photometricBilinear(t, c, g, s, r) * max(gamma.y, 0.0f);
    // Accepted with probability density / envelope as a float (24 bits),
    // truncated to a multiple of 2^-32: the 32-bit word against the ratio
    // in 2^-32 units.
    PRECISE float threshold = (density / envelope) * 4294967296.0f;
    if (threshold >= 4294967296.0f || words.z < uint(threshold)) {
      PRECISE float cTurns = c0 + s * (c1 - c0);
      vec2 around = cosSin2Pi(cTurns < 1.0f ? cTurns : cTurns - 1.0f);
      PRECISE vec3 side = light.tangent * around.x + light.bitangent * around.y;
      PRECISE vec3 d = light.axis * gamma.x + side * gamma.y;
      direction = d;
      return 1.0f;
    }
  }
  return 0.0f;
}

// The index i of the ascending angles [first, first + n) with angle i <= x <
// angle i + 1, clamped to [0, n - 2].
FN uint photometricInterval(uint first, uint n, float x) {
  uint low = 0u;
  uint high = n - 1u;
  while (high - low > 1u) {
    uint middle = (low + high) / 2u;
    if (readSceneFloat(first + middle) <= x) low = middle;
    else high = middle;
  }
  return low;
}

// Camera paths (light_arrival.h): the table's intensity towards `point`
// over its flux, per watt and steradian.
FN float photometricLightArrival(LightRecord light, vec3 point, OUT(vec3) lightPoint) {
  lightPoint = light.position;
  PhotometricLayout t = photometricTable(light);
  PRECISE vec3 away = point - light.position;
  PRECISE float along = dot3(away, light.axis);
  PRECISE float x = dot3(away, light.tangent);
  PRECISE float y = dot3(away, light.bitangent);
  PRECISE float across = sqrt(x * x + y * y);
  PRECISE float gTurns = polyAtan2(across, along) * 0.159154943f;  // 1 / (2 pi)
  PRECISE float cAngle = polyAtan2(y, x);
  PRECISE float cTurns = (cAngle < 0.0f ? cAngle + 6.28318531f : cAngle) * 0.159154943f;
  float gLow = readSceneFloat(t.gFirst);
  float gHigh = readSceneFloat(t.gFirst + t.nG - 1u);
  if (!(gTurns >= gLow && gTurns <= gHigh)) return 0.0f;
  uint c = photometricInterval(t.cFirst, t.nC, cTurns);
  uint g = photometricInterval(t.gFirst, t.nG, gTurns);
  float c0 = readSceneFloat(t.cFirst + c);
  float c1 = readSceneFloat(t.cFirst + c + 1u);
  float g0 = readSceneFloat(t.gFirst + g);
  float g1 = readSceneFloat(t.gFirst + g + 1u);
  PRECISE float s = min(max((cTurns - c0) / (c1 - c0), 0.0f), 1.0f);
  PRECISE float r = min(max((gTurns - g0) / (g1 - g0), 0.0f), 1.0f);
  return photometricBilinear(t, c, g, s, r);
}

#endif  // SPECTRACE_LIGHTS_PHOTOMETRIC_H
