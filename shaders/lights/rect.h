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

// Camera paths (light_arrival.h): a uniform point of the rect, whose
// radiance per watt is 1 / (pi area); over its density 1 / area that is
// cos / pi per steradian towards `point`.
FN float rectLightArrival(LightRecord light, vec3 point, float u, float v, OUT(vec3) lightPoint) {
  PRECISE float x = (u - 0.5f) * light.param0;
  PRECISE float y = (v - 0.5f) * light.param1;
  PRECISE vec3 p = light.position + light.tangent * x + light.bitangent * y;
  lightPoint = p;
  return lambertianArrival(light, p, point);
}

// Camera paths: the radiance per watt, 1 / (pi area), seen along the ray
// when it crosses the rect's emitting side at a distance in (0, reach).
FN float rectLightAlong(LightRecord light, vec3 origin, vec3 direction, float reach) {
  vec2 onPlane;
  if (!lambertianCrossing(light, origin, direction, reach, onPlane)) return 0.0f;
  if (!(abs(onPlane.x) <= 0.5f * light.param0) || !(abs(onPlane.y) <= 0.5f * light.param1)) return 0.0f;
  PRECISE float area = light.param0 * light.param1;
  return 0.318309886f / area;  // 1 / pi over the area
}

#endif  // SPECTRACE_LIGHTS_RECT_H
