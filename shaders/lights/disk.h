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

#endif  // SPECTRACE_LIGHTS_DISK_H
