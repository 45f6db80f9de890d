// Laser (kernel unit; host unit: host/lights/laser_light.cpp): collimated
// along `axis`, origins uniform over its cross-section (radius param0).
// Aimed: origins uniform over the disk (radius aimSpread, centre aimAxis.xy
// in (tangent, bitangent)) whose beams can reach the target; those outside
// the laser's own cross-section (radius^2 = aimAccept) carry nothing.
#ifndef SPECTRACE_LIGHTS_LASER_H
#define SPECTRACE_LIGHTS_LASER_H

FN float emitLaserBeam(LightRecord light, bool aimed, float ou, float ov, OUT(vec3) origin, OUT(vec3) direction) {
  float ratio = 1.0f;
  direction = light.axis;
  if (aimed) {
    vec2 p = sampleDisk(ou, ov, light.aimSpread);
    PRECISE vec2 q = vec2(light.aimAxis.x + p.x, light.aimAxis.y + p.y);
    PRECISE float q2 = q.x * q.x + q.y * q.y;
    PRECISE vec3 o = light.position + light.tangent * q.x + light.bitangent * q.y;
    origin = o;
    if (!(q2 <= light.aimAccept)) ratio = 0.0f;
  } else {
    vec2 p = sampleDisk(ou, ov, light.param0);
    PRECISE vec3 o = light.position + light.tangent * p.x + light.bitangent * p.y;
    origin = o;
  }
  return ratio;
}

#endif  // SPECTRACE_LIGHTS_LASER_H
