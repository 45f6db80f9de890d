// Shared by the point and spot units: a direction uniform in the cone
// (aimAxis, aimSpread = 1 - cos of its half angle) that holds the camera's
// target sphere (host/lights/light_shared.cpp, aimCone, derives it).
#ifndef SPECTRACE_LIGHTS_AIMED_CONE_H
#define SPECTRACE_LIGHTS_AIMED_CONE_H

FN vec3 aimedConeDirection(LightRecord light, float du, float dv) {
  return toFrame(sampleCone(du, dv, light.aimSpread), light.aimTangent, light.aimBitangent, light.aimAxis);
}

#endif  // SPECTRACE_LIGHTS_AIMED_CONE_H
