// Camera paths: the camera estimator (pbrt-v4's path, Mitsuba 3's path
// integrator, with next-event estimation), in the film's units, beside the
// light paths (trace.h). A path starts at a uniform point of a pixel of the
// stored window and a uniform point of the camera's entrance (a pinhole's or
// a thin lens's disk), and goes through
// the objects with the same materials as beams. At each diffuse vertex it
// samples a light (light_arrival.h); before any diffuse vertex it sees the
// emitters it crosses.
//
// Which estimator counts a path of light. A path is the light, the surfaces
// it meets, then the camera. The camera estimator counts exactly the paths
// whose first vertex after the light is a diffuse surface met by a light
// other than a laser (next-event estimation), and those that start on an
// emitter with an area (a disk, a rect, an emitting object) and meet no
// diffuse surface (seen directly); the light estimator counts the others
// (trace.h skips the camera's). Each path is counted once, so the sum is unbiased whenever each estimator is: a
// multiple importance sampling whose weights are 0 or 1 (Veach 1997, 9.2).
// The camera estimator alone (--estimator camera) misses the light's paths:
// lasers, and point and spot beams whose first surface is specular.
//
// Each path is unbiased as it stands: its light (chosen as a beam's is, in
// proportion to sampled power), wavelength (from the light's own table) and
// geometry are drawn with known densities, and its count is what it carries
// over them, in full-weight beams (LightRecord.cameraPathWeight,
// TraceConstants.cameraPathScale).
#ifndef SPECTRACE_CAMERA_PATH_H
#define SPECTRACE_CAMERA_PATH_H

#include "light_arrival.h"
#include "wavelengths.h"

// floor(u n / 2^64) for a 64-bit uniform u: an integer below n, each with
// probability within n / 2^64 of 1/n. Exact in 64-bit integers.
FN uint uniformBelow(uint64_t u, uint n) {
  uint64_t high = (u >> 32u) * uint64_t(n);
  uint64_t low = ((u & 0xFFFFFFFFul) * uint64_t(n)) >> 32u;
  return uint((high + low) >> 32u);
}

// The pixel of path `pathIndex`. Paths come in rounds of one per stored
// pixel; round r sends its j-th path to pixel (j + offset_r) mod pixels,
// offset_r uniform from (seed, r). So each path's pixel is uniform over the
// window whatever the number of paths (unbiased), and each whole round
// visits every pixel once (stratified: no pixel goes short of paths).
FN uvec2 cameraPathCell(uint64_t pathIndex) {
  uint pixels = constants.windowWidth * constants.windowHeight;
  uint64_t roundIndex = pathIndex / uint64_t(pixels);
  uint place = uint(pathIndex - roundIndex * uint64_t(pixels));
  uvec4 words = philox4x32(constants.seed, roundIndex, kRngBlockCameraRound);
  uint stored = place + uniformBelow(joinWords(words.x, words.y), pixels);
  if (stored >= pixels) stored -= pixels;
  uint row = stored / constants.windowWidth;
  return uvec2(constants.windowX0 + (stored - row * constants.windowWidth), constants.windowY0 + row);
}

// Counts `ratio` times each carried wavelength's share and its `factor`
// (e.g. its reflectance) into the film at `cell`, as one event.
FN void contributeWavelengths(INOUT(BeamTally) tally, uvec2 cell, PathWavelengths w, WavelengthFactors factor,
                              float ratio, float rounding) {
  WavelengthFactors count;
  for (uint j = 0u; j < kMaxWavelengthsPerPath; ++j) {
    PRECISE float c = ratio * factor.value[j] * w.share[j];
    count.value[j] = c;
  }
  contributeCounts(tally, cell, w, count, rounding);
}

// Next-event estimation at a diffuse vertex `at` of reflectance rho (per
// wavelength): a point of the path's light, counted when nothing (no
// object, not the camera's body) stands between. What the vertex sends back
// along the path is the light's irradiance there times rho / pi.
FN void cameraPathLightSample(LightRecord light, SurfaceHit at, WavelengthFactors rho, float throughput, uvec4 words,
                              uvec4 objectWords, uvec2 cell, PathWavelengths w, INOUT(BeamTally) tally) {
  vec3 lightPoint;
  float arrival =
      lightArrival(light, at.point, uniformFromWord(words.x), uniformFromWord(words.y), objectWords, lightPoint);
  if (!(arrival > 0.0f)) return;
  PRECISE vec3 toLight = lightPoint - at.point;
  PRECISE float distanceSq = dot3(toLight, toLight);
  PRECISE float distance = sqrt(distanceSq);
  PRECISE vec3 direction = toLight * (1.0f / distance);
  float cosSurface = dot3(direction, at.facing);
  if (!(cosSurface > 0.0f)) return;
  // The shadow ray runs from its own start (offset by up to 256 ulps of the
  // point, more than the margin) straight at the light point, and stops
  // just short of it: an emitting object's own surface lies there, which a
  // ray along `direction` could meet sooner where it crosses the surface
  // at a grazing angle.
  vec3 start = offsetOffSurface(at.point, at.facing);
  PRECISE vec3 startToLight = lightPoint - start;
  PRECISE float shadowLength = sqrt(dot3(startToLight, startToLight));
  PRECISE vec3 shadowDirection = startToLight * (1.0f / shadowLength);
  PRECISE float reach = shadowLength * 0.99999f;
  ObjectHit blocker;
  if (intersectObjects(start, shadowDirection, reach, true, blocker)) return;
  bool counted;
  uvec2 unusedCell;
  float unusedTransmission;
  float toCamera = intersectCamera(start, shadowDirection, w.lambda[0], counted, unusedCell, unusedTransmission);
  if (toCamera >= 0.0f && toCamera < reach) return;
  PRECISE float ratio = throughput * 0.318309886f * arrival * cosSurface / distanceSq;  // rho / pi, rho below
  contributeWavelengths(tally, cell, w, rho, ratio, uniformFromWord(words.z));
}

// Camera path `pathIndex`: traced, and its counts added to the film (or
// noted in `tally`, as a beam's are).
FN void traceCameraPath(uint64_t pathIndex, INOUT(BeamTally) tally) {
  uint lightIndex = chooseLight(constants.seed, pathIndex, kRngBlockCameraLight);
  LightRecord light = readLight(lightIndex);
  bool objectLight = SPECTRACE_LIGHT_ENABLED(kLightObject) && light.type == kLightObject;
  if (!lightLightsPoints(light)) return;
  uvec4 start = philox4x32(constants.seed, pathIndex, kRngBlockCameraStart);
  uvec4 spectral = philox4x32(constants.seed, pathIndex, kRngBlockCameraSpectral);
  PathWavelengths w = drawPathWavelengths(light, joinWords(spectral.x, spectral.y), uniformFromWord(spectral.z),
                                          constants.wavelengthsPerPath);
  uvec2 cell = cameraPathCell(pathIndex);
  vec3 onSensor = sensorPointInCell(cell, uniformFromWord(start.x), uniformFromWord(start.y), true);
  float apertureArea;
  vec3 origin = cameraConnectionPoint(uniformFromWord(start.z), uniformFromWord(start.w), apertureArea);
  PRECISE vec3 toAperture = origin - onSensor;
  PRECISE vec3 throughAperture = toAperture * (1.0f / sqrt(dot3(toAperture, toAperture)));
  vec3 direction = cameraPathDirection(onSensor, origin, throughAperture);
  // The geometry term between the sensor and the aperture's planes,
  // cos^4 / distance^2, over their densities (cameraPathScale). Through a
  // lens, cos is the scene side's: the solid angle of the light that a
  // sensor area dA receives through a lens point is cos^3 dA / s^2
  // (its slope changes by dA / s^2), which, times the cosine at the lens,
  // is the pinhole's cos^4 / s^2 with that angle.
  PRECISE float cosSq = direction.z * direction.z;
  PRECISE float throughput = cosSq * cosSq * constants.cameraPathScale * light.cameraPathWeight;
  bool afterDiffuse = false;
  float rounding = uniformFromWord(spectral.w);
  for (uint vertex = 0u; vertex <= constants.maxBounces; ++vertex) {
    ObjectHit hit = noObjectHit();
    bool metObject = SPECTRACE_OBJECTS && intersectObjects(origin, direction, 3.0e38f, false, hit);
    float reach = metObject ? hit.t : 3.0e38f;
    // A light path ends where it meets the camera's body; so does this.
    bool metCamera = false;
    if (vertex > 0u) {
      bool counted;
      uvec2 unusedCell;
      float unusedTransmission;
      float toCamera = intersectCamera(origin, direction, w.lambda[0], counted, unusedCell, unusedTransmission);
      metCamera = toCamera >= 0.0f && toCamera < reach;
      if (metCamera) reach = toCamera;
    }
    // After a diffuse vertex the light sample counted the emitter instead.
    if (!afterDiffuse && lightSeenDirectly(light) && !objectLight) {
      float radiance = lightAlongRay(light, origin, direction, reach);
      if (radiance > 0.0f) contributeCounts(tally, cell, w, sharesTimes(w, throughput * radiance), rounding);
    }
    if (!metObject || metCamera) return;
    Primitive surface = readPrimitive(hit.primitive);
    PRECISE vec3 found = origin + direction * hit.t;
    vec3 n = primitiveNormal(surface, found);
    // An emitting object is seen where the path meets its surface.
    if (!afterDiffuse && objectLight) {
      float radiance = objectLightAlong(light, lightIndex, surface, n, direction);
      if (radiance > 0.0f) contributeCounts(tally, cell, w, sharesTimes(w, throughput * radiance), rounding);
    }
    if (vertex == constants.maxBounces) return;
    Material material = readMaterial(surface.material);
    if (materialEndsEveryBeam(material)) return;
    SurfaceHit at;
    at.point = pointOnSurface(surface, found, n);
    at.fromOutside = dot3(direction, n) < 0.0f;
    at.facing = at.fromOutside ? n : -n;
    uvec4 words = philox4x32(constants.seed, pathIndex, kRngBlockCameraVertex + 2u * vertex);
    rounding = uniformFromWord(words.w);
    if (isMaterial(material, kMaterialDiffuse)) {
      WavelengthFactors rho = reflectancesAt(material, w);
      uvec4 objectWords = objectLight ? philox4x32(constants.seed, pathIndex, kRngBlockCameraEmitterPoint + vertex)
                                      : uvec4(0u, 0u, 0u, 0u);
      cameraPathLightSample(light, at, rho, throughput,
                            philox4x32(constants.seed, pathIndex, kRngBlockCameraVertex + 2u * vertex + 1u), objectWords,
                            cell, w, tally);
      // Cosine-weighted on: the BRDF times the cosine over the density is
      // rho, which the roulette keeps (surviveReflectance).
      if (!surviveReflectance(rho, uniformFromWord(words.x), w)) return;
      bounceDiffusely(at, words, origin, direction);
      afterDiffuse = true;
    } else if (isMaterial(material, kMaterialMirror)) {
      if (!scatterMirror(material, at, words, w, origin, direction, afterDiffuse)) return;
    } else if (isMaterial(material, kMaterialDielectric)) {
      scatterDielectric(material, at, words, w, origin, direction, afterDiffuse);
      // Radiance over the index squared is what crossing keeps: seen from
      // this side of the surface it is eta^2 (eta = this side's index over
      // the other's) of what it is beyond.
      if (dot3(direction, at.facing) < 0.0f) {
        float index = refractiveIndexAt(material, w.lambda[0]);
        PRECISE float eta = at.fromOutside ? 1.0f / index : index;
        throughput = throughput * (eta * eta);
      }
    } else {
      return;
    }
  }
}

#endif  // SPECTRACE_CAMERA_PATH_H
