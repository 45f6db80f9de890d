// Emitting object (kernel unit; host unit: host/lights/object_light.cpp):
// a Lambertian emitter over an object's primitives, kept in the scene data
// (device_shared.h, kObjectEmitterHeaderWords) with the alias columns that
// choose one by area. A uniform point on it (shapes/<primitive>.h), the
// face it leaves (either, for a two-sided emitter), cosine-weighted about
// that face, from just off the surface (offsetOffSurface), so the object
// itself is not met at the start. Camera paths draw the same points, and
// see the object where they meet its primitives (Primitive.emitter).
#ifndef SPECTRACE_LIGHTS_OBJECT_H
#define SPECTRACE_LIGHTS_OBJECT_H

FN Primitive readEmitterPrimitive(uint first) {
  Primitive p;
  p.a = vec3(readSceneFloat(first), readSceneFloat(first + 1u), readSceneFloat(first + 2u));
  p.type = readSceneWord(first + 3u);
  p.b = vec3(readSceneFloat(first + 4u), readSceneFloat(first + 5u), readSceneFloat(first + 6u));
  p.material = readSceneWord(first + 7u);
  p.c = vec3(readSceneFloat(first + 8u), readSceneFloat(first + 9u), readSceneFloat(first + 10u));
  p.emitter = 0u;
  return p;
}

// A point uniform by area over the object (a primitive through the alias
// columns from the 64-bit uniform, then a uniform point on it from u, v),
// and that primitive's normal there.
FN vec3 objectLightPoint(LightRecord light, uint64_t aliasUniform, float u, float v, OUT(vec3) n) {
  uint aliasBits = readSceneWord(light.dataFirst + 1u);
  uint aliasFirst = light.dataFirst + kObjectEmitterHeaderWords;
  uint chosen = sceneAliasLookup(aliasFirst, aliasBits, aliasUniform);
  Primitive p = readEmitterPrimitive(aliasFirst + 4u * (1u << aliasBits) + kPrimitiveWords * chosen);
  n = vec3(0.0f, 0.0f, 1.0f);
  vec3 point = p.a;
  if (isPrimitive(p, kPrimitiveTriangle)) point = sampleTrianglePoint(p, u, v, n);
  else if (isPrimitive(p, kPrimitiveRect)) point = sampleRectPoint(p, u, v, n);
  else if (isPrimitive(p, kPrimitiveDisk)) point = sampleDiskPoint(p, u, v, n);
  else if (isPrimitive(p, kPrimitiveSphere)) point = sampleSpherePoint(p, u, v, n);
  return point;
}

FN bool objectLightTwoSided(LightRecord light) { return readSceneWord(light.dataFirst + 2u) != 0u; }

// Returns the weight ratio, 1: every beam carries the same power.
FN float emitObjectBeam(LightRecord light, uvec4 geometry, uint64_t beamIndex, OUT(vec3) origin,
                        OUT(vec3) direction) {
  uvec4 words = philox4x32(constants.seed, beamIndex, kRngBlockEmitterPoint);
  vec3 n;
  vec3 point = objectLightPoint(light, joinWords(geometry.x, geometry.y), uniformFromWord(words.x),
                                uniformFromWord(words.y), n);
  vec3 face = objectLightTwoSided(light) && (words.z & 1u) != 0u ? -n : n;
  vec3 t;
  vec3 b;
  frameAround(face, t, b);
  direction = toFrame(sampleCosineHemisphere(uniformFromWord(geometry.z), uniformFromWord(geometry.w)), t, b, face);
  origin = offsetOffSurface(point, face);
  return 1.0f;
}

// Camera paths (light_arrival.h): a point uniform over the surface, whose
// radiance per watt is 1 / (pi area) on an emitting face (half that on
// each face of a two-sided one); over its density 1 / area that is
// cos / pi per steradian towards `point` (|cos| / 2 pi, two-sided).
FN float objectLightArrival(LightRecord light, vec3 point, uvec4 words, OUT(vec3) lightPoint) {
  vec3 n;
  PRECISE vec3 p = objectLightPoint(light, joinWords(words.x, words.y), uniformFromWord(words.z),
                                    uniformFromWord(words.w), n);
  lightPoint = p;
  PRECISE vec3 away = point - p;
  PRECISE float cosTheta = dot3(away, n) / sqrt(dot3(away, away));
  if (objectLightTwoSided(light)) return abs(cosTheta) * 0.159154943f;  // 1 / 2 pi
  return cosTheta > 0.0f ? cosTheta * 0.318309886f : 0.0f;             // 1 / pi
}

// Camera paths: the radiance per watt seen along a ray that meets the
// primitive `surface` (of normal n where it is met), when the primitive is
// this light's (lightIndex) and the ray meets an emitting face.
FN float objectLightAlong(LightRecord light, uint lightIndex, Primitive surface, vec3 n, vec3 direction) {
  if (surface.emitter != lightIndex + 1u) return 0.0f;
  PRECISE float area = readSceneFloat(light.dataFirst + 3u);
  if (objectLightTwoSided(light)) return 0.159154943f / area;  // 1 / (2 pi area)
  return dot3(direction, n) < 0.0f ? 0.318309886f / area : 0.0f;
}

#endif  // SPECTRACE_LIGHTS_OBJECT_H
