// Point light (kernel unit; host unit: host/lights/point_light.cpp):
// isotropic from `position`. Aimed: uniform in the cone holding the
// target, every beam with weight ratio 1.
#ifndef SPECTRACE_LIGHTS_POINT_H
#define SPECTRACE_LIGHTS_POINT_H

FN float emitPointBeam(LightRecord light, bool aimed, float du, float dv, OUT(vec3) origin, OUT(vec3) direction) {
  origin = light.position;
  direction = aimed ? aimedConeDirection(light, du, dv) : sampleSphere(du, dv);
  return 1.0f;
}

// Camera paths (light_arrival.h): isotropic, so 1 / (4 pi) of each watt
// per steradian towards any point.
FN float pointLightArrival(LightRecord light, OUT(vec3) lightPoint) {
  lightPoint = light.position;
  return 0.0795774715f;  // 1 / (4 pi)
}

#endif  // SPECTRACE_LIGHTS_POINT_H
