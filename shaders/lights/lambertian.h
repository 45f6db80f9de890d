// Shared by the disk and rect units: one-sided Lambertian emission from an
// origin already drawn on the emitter.
#ifndef SPECTRACE_LIGHTS_LAMBERTIAN_H
#define SPECTRACE_LIGHTS_LAMBERTIAN_H

// Analog: cosine-weighted about the light's axis.
FN vec3 lambertianDirection(LightRecord light, float du, float dv) {
  return toFrame(sampleCosineHemisphere(du, dv), light.tangent, light.bitangent, light.axis);
}

// Aimed: uniform in the cone from `origin` that holds the target sphere,
// when that cone is narrower than a hemisphere's worth of cosine-weighted
// emission (2h < 1); ratio cos(theta) 2h, the density cos(theta)/pi over
// 1/(2 pi h), scaled by aimWeightScale. Otherwise analog, with the light's
// constant ratio.
FN float emitLambertianAimed(LightRecord light, vec3 origin, float du, float dv, OUT(vec3) direction) {
  float ratio = 1.0f;
  PRECISE vec3 toCentre = constants.aimCentre - origin;
  PRECISE float distance = sqrt(dot3(toCentre, toCentre));
  PRECISE float sinHalf = constants.aimRadius / distance + SPECTRACE_AIM_SLACK;
  if (sinHalf * sinHalf < 0.75f) {
    float h = oneMinusCosFromSin(sinHalf);
    PRECISE vec3 coneAxis = toCentre / distance;
    vec3 t;
    vec3 b;
    frameAround(coneAxis, t, b);
    direction = toFrame(sampleCone(du, dv, h), t, b, coneAxis);
    PRECISE float cosTheta = dot3(direction, light.axis);
    PRECISE float weight = cosTheta * (2.0f * h) * light.aimWeightScale;
    ratio = cosTheta > 0.0f ? min(weight, 1.0f) : 0.0f;
  } else {
    direction = lambertianDirection(light, du, dv);
    ratio = min(light.aimWeightScale, 1.0f);
  }
  return ratio;
}

FN float emitLambertian(LightRecord light, bool aimed, vec3 origin, float du, float dv, OUT(vec3) direction) {
  float ratio = 1.0f;
  if (aimed) {
    ratio = emitLambertianAimed(light, origin, du, dv, direction);
  } else {
    direction = lambertianDirection(light, du, dv);
  }
  return ratio;
}

// Camera paths (the disk and rect units): per watt and steradian, what a
// point `lightPoint` drawn uniformly over the emitter sends towards
// `point`: cos(theta) / pi on the emitting side, 0 behind it.
FN float lambertianArrival(LightRecord light, vec3 lightPoint, vec3 point) {
  PRECISE vec3 away = point - lightPoint;
  PRECISE float cosTheta = dot3(away, light.axis) / sqrt(dot3(away, away));
  return cosTheta > 0.0f ? cosTheta * 0.318309886f : 0.0f;  // 1 / pi
}

// Where a ray crosses the emitter's plane from its emitting side, at a
// distance in (0, reach): the crossing in (tangent, bitangent) about the
// centre.
FN bool lambertianCrossing(LightRecord light, vec3 origin, vec3 direction, float reach, OUT(vec2) onPlane) {
  onPlane = vec2(0.0f, 0.0f);
  float facing = dot3(direction, light.axis);
  if (!(facing < 0.0f)) return false;
  PRECISE float t = dot3(light.position - origin, light.axis) / facing;
  if (!(t > 0.0f) || !(t < reach)) return false;
  PRECISE vec3 offset = origin + direction * t - light.position;
  onPlane = vec2(dot3(offset, light.tangent), dot3(offset, light.bitangent));
  return true;
}

#endif  // SPECTRACE_LIGHTS_LAMBERTIAN_H
