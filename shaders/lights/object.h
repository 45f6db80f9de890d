// Emitting object (kernel unit; host unit: host/lights/object_light.cpp):
// a Lambertian emitter over an object's primitives, kept in the scene data
// (device_shared.h, kObjectEmitterHeaderWords) with the alias columns that
// choose one by area. A uniform point on it (shapes/<primitive>.h), the
// face it leaves (either, for a two-sided emitter), cosine-weighted about
// that face, from just off the surface (offsetOffSurface), so the object
// itself is not met at the start.
#ifndef SPECTRACE_LIGHTS_OBJECT_H
#define SPECTRACE_LIGHTS_OBJECT_H

FN Primitive readEmitterPrimitive(uint first) {
  Primitive p;
  p.a = vec3(readSceneFloat(first), readSceneFloat(first + 1u), readSceneFloat(first + 2u));
  p.type = readSceneWord(first + 3u);
  p.b = vec3(readSceneFloat(first + 4u), readSceneFloat(first + 5u), readSceneFloat(first + 6u));
  p.material = readSceneWord(first + 7u);
  p.c = vec3(readSceneFloat(first + 8u), readSceneFloat(first + 9u), readSceneFloat(first + 10u));
  p.padding0 = 0u;
  return p;
}

// Returns the weight ratio, 1: every beam carries the same power.
FN float emitObjectBeam(LightRecord light, uvec4 geometry, uint64_t beamIndex, OUT(vec3) origin,
                        OUT(vec3) direction) {
  uint aliasBits = readSceneWord(light.dataFirst + 1u);
  bool twoSided = readSceneWord(light.dataFirst + 2u) != 0u;
  uint aliasFirst = light.dataFirst + kObjectEmitterHeaderWords;
  uint chosen = sceneAliasLookup(aliasFirst, aliasBits, joinWords(geometry.x, geometry.y));
  Primitive p = readEmitterPrimitive(aliasFirst + 4u * (1u << aliasBits) + kPrimitiveWords * chosen);
  uvec4 words = philox4x32(constants.seed, beamIndex, kRngBlockEmitterPoint);
  float u = uniformFromWord(words.x);
  float v = uniformFromWord(words.y);
  vec3 n = vec3(0.0f, 0.0f, 1.0f);
  vec3 point = p.a;
  if (p.type == kPrimitiveTriangle) point = sampleTrianglePoint(p, u, v, n);
  else if (p.type == kPrimitiveRect) point = sampleRectPoint(p, u, v, n);
  else if (p.type == kPrimitiveDisk) point = sampleDiskPoint(p, u, v, n);
  else if (p.type == kPrimitiveSphere) point = sampleSpherePoint(p, u, v, n);
  vec3 face = twoSided && (words.z & 1u) != 0u ? -n : n;
  vec3 t;
  vec3 b;
  frameAround(face, t, b);
  direction = toFrame(sampleCosineHemisphere(uniformFromWord(geometry.z), uniformFromWord(geometry.w)), t, b, face);
  origin = offsetOffSurface(point, face);
  return 1.0f;
}

#endif  // SPECTRACE_LIGHTS_OBJECT_H
