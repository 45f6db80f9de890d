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

#endif  // SPECTRACE_LIGHTS_LAMBERTIAN_H
