// A lens system (host/camera/lens_system_camera.cpp): spherical and flat
// surfaces centred on the view axis, traced beam by beam with the index of
// each beam's own wavelength, so vignetting and chromatic aberration come
// out of the trace rather than from a model of them.
//
// The barrel opens in the entrance disk (cameras/entrance_disk.h): at
// cameraFrontZ, the first surface's foremost point, of the first surface's
// semi-aperture (radius squared cameraParams.x). A beam enters there, or
// meets the barrel; camera connections end on a uniform point of it, so
// every path into the lens is one a connection can make.
// cameraParams.y, .z: the camera body's half width and height (the sensor's
// or the widest surface's, whichever is larger); .w: 1 when an index
// depends on the wavelength.
//
// The table at cameraDataFirst: the surface count, then kLensSurfaceWords
// words a surface, front to back: its vertex's z, its curvature 1/R (0:
// flat; R > 0 when the centre lies towards the sensor), its semi-aperture
// squared, and the Sellmeier b, c of the medium behind it (air: all 0).
// The image is inverted on the sensor.
#ifndef SPECTRACE_CAMERAS_LENS_SYSTEM_H
#define SPECTRACE_CAMERAS_LENS_SYSTEM_H

#include "cameras/entrance_disk.h"

struct LensSurface {
  float vertexZ;
  float curvature;
  float apertureSq;
  vec3 sellmeierB;
  vec3 sellmeierC;
};

FN LensSurface readLensSurface(uint surface) {
  uint at = constants.cameraDataFirst + 1u + surface * kLensSurfaceWords;
  LensSurface s;
  s.vertexZ = readSceneFloat(at);
  s.curvature = readSceneFloat(at + 1u);
  s.apertureSq = readSceneFloat(at + 2u);
  s.sellmeierB = vec3(readSceneFloat(at + 3u), readSceneFloat(at + 4u), readSceneFloat(at + 5u));
  s.sellmeierC = vec3(readSceneFloat(at + 6u), readSceneFloat(at + 7u), readSceneFloat(at + 8u));
  return s;
}

// Where the ray p + t d meets surface s's cap, the part of its sphere on
// the vertex's side of the centre (the semi-aperture is at most |R|), as
// the least t >= 0 there (0: a flat surface in the entrance plane); false
// if it does not. In the surface's own coordinates (x, y, w = vertexZ - z),
// the sphere through the vertex is curvature (x^2 + y^2 + w^2) - 2 w = 0,
// a quadratic in t whose roots are taken without cancellation (q, then
// cq / q and q / curvature), and which on a flat surface has the one root
// cq / q.
FN bool lensCapCrossing(LensSurface s, vec3 p, vec3 d, OUT(float) t) {
  t = 0.0f;
  PRECISE float ow = s.vertexZ - p.z;
  PRECISE float dw = -d.z;
  PRECISE float oo = p.x * p.x + p.y * p.y + ow * ow;
  PRECISE float od = p.x * d.x + p.y * d.y + ow * dw;
  PRECISE float bq = s.curvature * od - dw;
  PRECISE float cq = s.curvature * oo - 2.0f * ow;
  PRECISE float disc = bq * bq - s.curvature * cq;
  if (!(disc >= 0.0f)) return false;
  PRECISE float root = sqrt(disc);
  PRECISE float q = bq <= 0.0f ? root - bq : -bq - root;
  if (q == 0.0f) return false;
  PRECISE float t0 = cq / q;
  PRECISE float t1 = s.curvature != 0.0f ? q / s.curvature : -1.0f;
  float first = min(t0, t1);
  float second = max(t0, t1);
  // On the cap: 1 - curvature w > 0 (the normal's z component).
  PRECISE float w0 = ow + first * dw;
  PRECISE float w1 = ow + second * dw;
  if (first >= 0.0f && 1.0f - s.curvature * w0 > 0.0f) {
    t = first;
    return true;
  }
  if (second >= 0.0f && 1.0f - s.curvature * w1 > 0.0f) {
    t = second;
    return true;
  }
  return false;
}

// A beam from beyond the entrance travelling towards -z, at wavelength
// lambda (nm), through every surface: true when it passes each within its
// semi-aperture, refracting by Snell's law, and reaches the sensor plane at
// `onSensor`. `transmission`: the product of 1 - Fresnel reflectance
// (unpolarised) over its surfaces, what it keeps of its flux; reflected
// light, and light totally reflected, leaves the beam (absorbed by the
// barrel).
FN bool lensSystemCrossing(vec3 origin, vec3 direction, float lambda, OUT(vec2) onSensor,
                           OUT(float) transmission) {
  onSensor = vec2(0.0f, 0.0f);
  transmission = 0.0f;
  vec2 atFront;
  if (!crossesEntranceDisk(origin, direction, atFront)) return false;
  vec3 p = vec3(atFront.x, atFront.y, constants.cameraFrontZ);
  vec3 d = direction;
  float indexBefore = 1.0f;
  float kept = 1.0f;
  uint count = readSceneWord(constants.cameraDataFirst);
  for (uint i = 0u; i < count; ++i) {
    LensSurface s = readLensSurface(i);
    float t;
    if (!lensCapCrossing(s, p, d, t)) return false;
    PRECISE vec3 hit = p + d * t;
    if (!(hit.x * hit.x + hit.y * hit.y <= s.apertureSq)) return false;
    p = hit;
    float indexAfter = sellmeierIndexAt(s.sellmeierB, s.sellmeierC, lambda);
    if (indexAfter == indexBefore) continue;  // a stop, or glass cemented to the same glass
    PRECISE float w = s.vertexZ - hit.z;
    PRECISE vec3 normal = vec3(s.curvature * hit.x, s.curvature * hit.y, 1.0f - s.curvature * w);
    PRECISE vec3 unitNormal = normal * (1.0f / sqrt(dot3(normal, normal)));
    vec3 facing = dot3(d, unitNormal) < 0.0f ? unitNormal : -unitNormal;
    PRECISE float eta = indexBefore / indexAfter;
    PRECISE float cosIncident = -dot3(d, facing);
    PRECISE float sinSqTransmitted = eta * eta * max(1.0f - cosIncident * cosIncident, 0.0f);
    if (sinSqTransmitted >= 1.0f) return false;  // totally reflected
    PRECISE float cosTransmitted = sqrt(1.0f - sinSqTransmitted);
    PRECISE float keptHere = kept * (1.0f - fresnelDielectric(cosIncident, cosTransmitted, eta));
    kept = keptHere;
    PRECISE vec3 refracted = d * eta + facing * (eta * cosIncident - cosTransmitted);
    d = refracted * (1.0f / sqrt(dot3(refracted, refracted)));
    indexBefore = indexAfter;
  }
  if (!(d.z < 0.0f)) return false;
  PRECISE float toSensor = -p.z / d.z;
  PRECISE float hx = p.x + toSensor * d.x;
  PRECISE float hy = p.y + toSensor * d.y;
  onSensor = vec2(hx, hy);
  transmission = kept;
  return true;
}

#endif  // SPECTRACE_CAMERAS_LENS_SYSTEM_H
