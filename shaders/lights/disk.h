// Disk light (kernel unit; host unit: host/lights/disk_light.cpp): origins
// uniform over the disk of radius param0 about `position` in (tangent,
// bitangent), Lambertian towards `axis` (lambertian.h).
#ifndef SPECTRACE_LIGHTS_DISK_H
#define SPECTRACE_LIGHTS_DISK_H

FN vec3 diskOrigin(LightRecord light, float ou, float ov) {
  vec2 p = sampleDisk(ou, ov, light.param0);
  PRECISE vec3 o = light.position + light.tangent * p.x + light.bitangent * p.y;
  return o;
}

FN float emitDiskBeam(LightRecord light, bool aimed, float ou, float ov, float du, float dv, OUT(vec3) origin,
                      OUT(vec3) direction) {
  origin = diskOrigin(light, ou, ov);
  return emitLambertian(light, aimed, origin, du, dv, direction);
}

// Camera paths (light_arrival.h), as the rect's (rect.h): a uniform point
// of the disk, cos / pi per steradian per watt towards `point`.
FN float diskLightArrival(LightRecord light, vec3 point, float u, float v, OUT(vec3) lightPoint) {
  lightPoint = diskOrigin(light, u, v);
  return lambertianArrival(light, lightPoint, point);
}

// Camera paths: 1 / (pi area) per watt where the ray crosses the disk's
// emitting side at a distance in (0, reach).
FN float diskLightAlong(LightRecord light, vec3 origin, vec3 direction, float reach) {
  vec2 onPlane;
  if (!lambertianCrossing(light, origin, direction, reach, onPlane)) return 0.0f;
  PRECISE float radiusSq = onPlane.x * onPlane.x + onPlane.y * onPlane.y;
  if (!(radiusSq <= light.param0 * light.param0)) return 0.0f;
  PRECISE float area = 3.14159265f * light.param0 * light.param0;
  return 0.318309886f / area;  // 1 / pi over the area
}

#endif  // SPECTRACE_LIGHTS_DISK_H
