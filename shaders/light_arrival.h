// What a light gives a camera path (camera_path.h), through its type's unit
// (lights/<type>.h), as emit.h gives a beam: at a point, a light point drawn
// from the light and the power per watt and steradian it sends towards the
// point (next-event estimation); along a ray, the radiance per watt of an
// emitter the ray sees. Watts are the light's traced power, so a light's
// spectrum (its table) stays out of it.
#ifndef SPECTRACE_LIGHT_ARRIVAL_H
#define SPECTRACE_LIGHT_ARRIVAL_H

#include "emit.h"

// Whether camera paths can reach the light through a surface point: all but
// the laser, whose collimated beam lights a point from one direction only.
FN bool lightLightsPoints(LightRecord light) { return light.type != kLightLaser; }

// Whether a camera ray can see the light itself: the emitters with an area.
FN bool lightSeenDirectly(LightRecord light) {
  return light.type == kLightDisk || light.type == kLightRect || light.type == kLightObject;
}

// A point of `light` for `point` from two uniforms (lightPoint; an emitting
// object draws its own four words, `objectWords`), and what the light
// sends from there towards `point` per watt and steradian: the irradiance
// at `point` is that, times the cosine there, over the squared distance.
// 0: nothing (outside a spot's cone, behind an emitter).
FN float lightArrival(LightRecord light, vec3 point, float u, float v, uvec4 objectWords, OUT(vec3) lightPoint) {
  lightPoint = light.position;
  float arrival = 0.0f;
  if (SPECTRACE_LIGHT_ENABLED(kLightPoint) && light.type == kLightPoint) {
    arrival = pointLightArrival(light, lightPoint);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightSpot) && light.type == kLightSpot) {
    arrival = spotLightArrival(light, point, lightPoint);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightDisk) && light.type == kLightDisk) {
    arrival = diskLightArrival(light, point, u, v, lightPoint);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightRect) && light.type == kLightRect) {
    arrival = rectLightArrival(light, point, u, v, lightPoint);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightPhotometric) && light.type == kLightPhotometric) {
    arrival = photometricLightArrival(light, point, lightPoint);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightObject) && light.type == kLightObject) {
    arrival = objectLightArrival(light, point, objectWords, lightPoint);
  }
  return arrival;
}

// The radiance per watt seen along the ray (origin, direction) from `light`
// where the ray crosses it at a distance in (0, reach); 0 where it does not.
// (An emitting object is an object: camera_path.h sees it where it meets
// its primitives, objectLightAlong.)
FN float lightAlongRay(LightRecord light, vec3 origin, vec3 direction, float reach) {
  float radiance = 0.0f;
  if (SPECTRACE_LIGHT_ENABLED(kLightDisk) && light.type == kLightDisk) {
    radiance = diskLightAlong(light, origin, direction, reach);
  } else if (SPECTRACE_LIGHT_ENABLED(kLightRect) && light.type == kLightRect) {
    radiance = rectLightAlong(light, origin, direction, reach);
  }
  return radiance;
}

#endif  // SPECTRACE_LIGHT_ARRIVAL_H
