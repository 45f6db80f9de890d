// Emission, the seed's getNextBeam(): which light, which wavelength, and
// the light's own unit (lights/<type>.h) for origin, direction and weight.
#ifndef SPECTRACE_EMIT_H
#define SPECTRACE_EMIT_H

#include "lights/aimed_cone.h"
#include "lights/lambertian.h"
#include "lights/point.h"
#include "lights/spot.h"
#include "lights/disk.h"
#include "lights/rect.h"
#include "lights/laser.h"
#include "lights/photometric.h"
// An emitting object draws points on its primitives (their kernel units).
#include "shapes/shape_shared.h"
#include "shapes/triangle.h"
#include "shapes/rect.h"
#include "shapes/disk.h"
#include "shapes/sphere.h"
#include "lights/object.h"

// The entry an alias table of 2^bits columns from column `first` draws for
// the 64-bit uniform u (host/spectrum/alias_table.h): O(1), one or two
// reads, with each entry's probability exactly its integer CDF width.
FN uint aliasLookup(uint first, uint bits, uint64_t u) {
  uint column = bits == 0u ? 0u : uint(u >> (64u - bits));
  AliasColumn entry = readAliasColumn(first + column);
  return (u << bits) < entry.threshold ? column : entry.alias;
}

// A light in proportion to its sampled power, from a 64-bit uniform of
// block `block` (drawn only when there is a choice): a beam's from
// kRngBlockLight, a camera path's from kRngBlockCameraLight.
FN uint chooseLight(uint64_t seed, uint64_t index, uint block) {
  uint lightIndex = 0u;
  if (SPECTRACE_SELECT_LIGHT) {
    uvec4 select = philox4x32(seed, index, block);
    lightIndex = aliasLookup(0u, constants.lightAliasBits, joinWords(select.x, select.y));
  }
  return lightIndex;
}

// A wavelength from a light's spectral table: the interval through its
// alias columns from a 64-bit uniform, the position inside it in closed form.
FN float drawWavelength(LightRecord light, uint64_t intervalUniform, float positionUniform) {
  uint intervalIndex = light.spectralFirst + aliasLookup(light.spectralAliasFirst, light.spectralAliasBits, intervalUniform);
  SpectralInterval interval = readInterval(intervalIndex);
  return wavelengthInInterval(interval.lambda0, interval.width, interval.slope, positionUniform);
}

// Origin and direction of beam `beamIndex` from `light` from the four words
// of its geometry block (kRngBlockGeometry), through the light type's unit,
// aimed where the host set it up; returns the weight ratio (emission
// density / sampling density, over the light's largest such value; 0: the
// beam carries nothing).
FN float emitLightBeam(LightRecord light, uvec4 geometry, uint64_t beamIndex, OUT(vec3) origin, OUT(vec3) direction) {
  float ou = uniformFromWord(geometry.x);
  float ov = uniformFromWord(geometry.y);
  float du = uniformFromWord(geometry.z);
  float dv = uniformFromWord(geometry.w);
  bool aimed = SPECTRACE_AIM && light.aimed != 0u;
  float ratio = 1.0f;
  origin = light.position;
  direction = light.axis;
  if (SPECTRACE_LIGHT_ENABLED(kLightPoint) && light.type == kLightPoint) {
    ratio = emitPointBeam(light, aimed, du, dv, origin, direction);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightSpot) && light.type == kLightSpot) {
    ratio = emitSpotBeam(light, aimed, du, dv, origin, direction);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightDisk) && light.type == kLightDisk) {
    ratio = emitDiskBeam(light, aimed, ou, ov, du, dv, origin, direction);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightRect) && light.type == kLightRect) {
    ratio = emitRectBeam(light, aimed, ou, ov, du, dv, origin, direction);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightLaser) && light.type == kLightLaser) {
    ratio = emitLaserBeam(light, aimed, ou, ov, origin, direction);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightPhotometric) && light.type == kLightPhotometric) {
    ratio = emitPhotometricBeam(light, geometry, beamIndex, direction);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightObject) && light.type == kLightObject) {
    ratio = emitObjectBeam(light, geometry, beamIndex, origin, direction);
  }
  return ratio;
}

#endif  // SPECTRACE_EMIT_H
