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

#endif  // SPECTRACE_LIGHTS_SPOT_H
