// Spot light (kernel unit; host unit: host/lights/spot_light.cpp): uniform
// in solid angle inside the cone about `axis` with 1 - cos(half angle) =
// param0. Aimed: uniform in the cone holding the target; beams outside the
// spot's own cone (sin^2 of its half angle = aimAccept) carry nothing.
#ifndef SPECTRACE_LIGHTS_SPOT_H
#define SPECTRACE_LIGHTS_SPOT_H

FN float emitSpotBeam(LightRecord light, bool aimed, float du, float dv, OUT(vec3) origin, OUT(vec3) direction) {
  origin = light.position;
  float ratio = 1.0f;
  if (aimed) {
    direction = aimedConeDirection(light, du, dv);
    vec3 off = cross3(direction, light.axis);
    if (!(dot3(direction, light.axis) > 0.0f) || !(dot3(off, off) <= light.aimAccept)) ratio = 0.0f;
  } else {
    direction = toFrame(sampleCone(du, dv, light.param0), light.tangent, light.bitangent, light.axis);
  }
  return ratio;
}

// Camera paths (light_arrival.h): 1 / (2 pi param0) of each watt per
// steradian inside the cone, none outside; 1 - cos of the angle off the
// axis as half the squared distance of the unit vectors (no cancellation
// for narrow cones).
FN float spotLightArrival(LightRecord light, vec3 point, OUT(vec3) lightPoint) {
  lightPoint = light.position;
  PRECISE vec3 away = point - light.position;
  PRECISE vec3 off = away * (1.0f / sqrt(dot3(away, away))) - light.axis;
  PRECISE float oneMinusCos = 0.5f * dot3(off, off);
  if (!(oneMinusCos <= light.param0)) return 0.0f;
  PRECISE float solidAngle = 6.28318531f * light.param0;  // 2 pi (1 - cos)
  return 1.0f / solidAngle;
}

#endif  // SPECTRACE_LIGHTS_SPOT_H
