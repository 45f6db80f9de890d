// Rect light (kernel unit; host unit: host/lights/rect_light.cpp): origins
// uniform over param0 x param1 metres about `position` along (tangent,
// bitangent), Lambertian towards `axis` (lambertian.h).
#ifndef SPECTRACE_LIGHTS_RECT_H
#define SPECTRACE_LIGHTS_RECT_H

FN float emitRectBeam(LightRecord light, bool aimed, float ou, float ov, float du, float dv, OUT(vec3) origin,
                      OUT(vec3) direction) {
  PRECISE float x = (ou - 0.5f) * light.param0;
  PRECISE float y = (ov - 0.5f) * light.param1;
  PRECISE vec3 o = light.position + light.tangent * x + light.bitangent * y;
  origin = o;
  return emitLambertian(light, aimed, origin, du, dv, direction);
}

#endif  // SPECTRACE_LIGHTS_RECT_H
