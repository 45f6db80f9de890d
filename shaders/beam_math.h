// Sampling and geometry maths of the shared kernel, written once in the
// common subset of GLSL and C++/GLM (kernel_lang.h). Only + - * / and sqrt
// are used: they are correctly rounded on both sides, unlike sin/cos, which
// are replaced by polynomials. The light units (lights/), emission
// (emit.h) and the sensor (sensor.h) build on these.
#ifndef SPECTRACE_BEAM_MATH_H
#define SPECTRACE_BEAM_MATH_H

#include "kernel_lang.h"

// (x >> 8) * 2^-24: exact in float32, in [0, 1 - 2^-24].
FN float uniformFromWord(uint x) { return float(x >> 8) * (1.0f / 16777216.0f); }

FN uint64_t joinWords(uint lo, uint hi) { return (uint64_t(hi) << 32) | uint64_t(lo); }

// cos and sin of 2*pi*u for u = k * 2^-24. Quadrant and octant reduction is
// exact; the polynomials are the Taylor series to x^11 / x^12 on
// [0, pi/4], whose truncation error (< 1e-11) is far below float rounding.
FN vec2 cosSin2Pi(float u) {
  PRECISE float q4 = u * 4.0f;               // exact
  uint quadrant = uint(q4);
  PRECISE float r = q4 - float(quadrant);    // exact, in [0, 1)
  bool upperHalf = r > 0.5f;
  PRECISE float rr = upperHalf ? 1.0f - r : r;  // exact, in [0, 0.5]
  PRECISE float x = rr * 1.57079632679489662f;  // angle in [0, pi/4]
  PRECISE float x2 = x * x;
  PRECISE float s = x * (1.0f + x2 * (-1.66666666666666667e-1f + x2 * (8.33333333333333333e-3f +
                    x2 * (-1.98412698412698413e-4f + x2 * (2.75573192239858907e-6f +
                    x2 * (-2.50521083854417188e-8f))))));
  PRECISE float c = 1.0f + x2 * (-0.5f + x2 * (4.16666666666666667e-2f + x2 * (-1.38888888888888889e-3f +
                    x2 * (2.48015873015873016e-5f + x2 * (-2.75573192239858907e-7f +
                    x2 * 2.08767569878680990e-9f)))));
  PRECISE float cq = upperHalf ? s : c;      // cos and sin of the angle within the quadrant
  PRECISE float sq = upperHalf ? c : s;
  vec2 result;
  if (quadrant == 0u) result = vec2(cq, sq);
  else if (quadrant == 1u) result = vec2(-sq, cq);
  else if (quadrant == 2u) result = vec2(-cq, -sq);
  else result = vec2(sq, -cq);
  return result;
}

// atan2(y, x) in [-pi, pi], radians, of finite y and x (0 for 0, 0). The
// ratio of the smaller to the larger magnitude, in [0, 1], is brought to
// [-tan(pi/12), tan(pi/12)] by atan z = pi/6 + atan((z sqrt3 - 1) / (z + sqrt3));
// there the Taylor series to w^13 truncates below 3e-10, far under float
// rounding. Quadrants and the swap are exact.
FN float polyAtan2(float y, float x) {
  PRECISE float ax = abs(x);
  PRECISE float ay = abs(y);
  bool swapped = ay > ax;
  PRECISE float small = swapped ? ax : ay;
  PRECISE float large = swapped ? ay : ax;
  PRECISE float z = large > 0.0f ? small / large : 0.0f;
  bool shifted = z > 0.267949192f;  // tan(pi/12)
  PRECISE float w = shifted ? (z * 1.73205081f - 1.0f) / (z + 1.73205081f) : z;
  PRECISE float w2 = w * w;
  PRECISE float a = w * (1.0f + w2 * (-0.333333333f + w2 * (0.2f + w2 * (-0.142857143f + w2 * (0.111111111f +
                    w2 * (-0.0909090909f + w2 * 0.0769230769f))))));
  if (shifted) a = a + 0.523598776f;  // pi/6
  if (swapped) a = 1.57079633f - a;   // pi/2
  if (x < 0.0f) a = 3.14159265f - a;  // pi
  return y < 0.0f ? -a : a;
}

// Position in [0, 1] within an interval whose density falls linearly from
// (1 - slope) to (1 + slope). Inverts the quadratic CDF in the form
// t = 2u / (a + sqrt((1-u) a^2 + u b^2)), which has no cancellation; all
// terms stay within [0, 4] whatever the SPD's absolute scale.
FN float sampleLinearInInterval(float u, float slope) {
  PRECISE float a = 1.0f - slope;
  PRECISE float b = 1.0f + slope;
  PRECISE float inner = (1.0f - u) * (a * a) + u * (b * b);
  PRECISE float denominator = a + sqrt(inner);
  PRECISE float t = denominator > 0.0f ? (2.0f * u) / denominator : 0.0f;
  return min(t, 1.0f);
}

// Wavelength in nm inside the chosen interval.
FN float wavelengthInInterval(float lambda0, float width, float slope, float u) {
  PRECISE float t = sampleLinearInInterval(u, slope);
  PRECISE float lambda = lambda0 + width * t;
  return lambda;
}

// Histogram bin of a wavelength in [lambdaMin, lambdaMin + bins / binsPerNm].
FN uint binOfWavelength(float lambda, float lambdaMin, float binsPerNm, uint bins) {
  PRECISE float x = (lambda - lambdaMin) * binsPerNm;
  uint bin = x > 0.0f ? uint(x) : 0u;
  return min(bin, bins - 1u);
}

// Uniform direction on the unit sphere (point lights).
FN vec3 sampleSphere(float u, float v) {
  PRECISE float z = 1.0f - 2.0f * u;                      // exact
  PRECISE float r = 2.0f * sqrt(u * (1.0f - u));          // sin(theta), no cancellation near the poles
  vec2 cs = cosSin2Pi(v);
  PRECISE vec3 d = vec3(r * cs.x, r * cs.y, z);
  return d;
}

// Local direction uniform in solid angle inside a cone around +z, where
// oneMinusCos = 1 - cos(half angle) (computed on the host in double).
FN vec3 sampleCone(float u, float v, float oneMinusCos) {
  PRECISE float h = u * oneMinusCos;                      // 1 - cos(theta)
  PRECISE float cosTheta = 1.0f - h;
  PRECISE float sinTheta = sqrt(h * (2.0f - h));          // no cancellation for narrow cones
  vec2 cs = cosSin2Pi(v);
  PRECISE vec3 d = vec3(sinTheta * cs.x, sinTheta * cs.y, cosTheta);
  return d;
}

// Cosine-weighted local direction around +z (Lambertian emitters).
FN vec3 sampleCosineHemisphere(float u, float v) {
  PRECISE float r = sqrt(u);
  PRECISE float z = sqrt(1.0f - u);                       // 1 - u is exact
  vec2 cs = cosSin2Pi(v);
  PRECISE vec3 d = vec3(r * cs.x, r * cs.y, z);
  return d;
}

// Point uniform on a disk of the given radius, in local (x, y).
FN vec2 sampleDisk(float u, float v, float radius) {
  PRECISE float r = radius * sqrt(u);
  vec2 cs = cosSin2Pi(v);
  PRECISE vec2 p = vec2(r * cs.x, r * cs.y);
  return p;
}

FN vec3 toFrame(vec3 local, vec3 tangent, vec3 bitangent, vec3 axis) {
  PRECISE vec3 w = tangent * local.x + bitangent * local.y + axis * local.z;
  return w;
}

// Dot and cross products with a fixed order of operations (the built-ins'
// order, and whether they fuse, is up to the compiler).
FN float dot3(vec3 a, vec3 b) {
  PRECISE float d = a.x * b.x + a.y * b.y + a.z * b.z;
  return d;
}
FN vec3 cross3(vec3 a, vec3 b) {
  PRECISE vec3 c = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  return c;
}

// A frame (t, b) completing the unit vector n (Duff et al. 2017, branchless
// orthonormal basis; the host builds light frames the same way in double).
FN void frameAround(vec3 n, OUT(vec3) t, OUT(vec3) b) {
  float sign = n.z >= 0.0f ? 1.0f : -1.0f;
  PRECISE float a = -1.0f / (sign + n.z);
  PRECISE float c = n.x * n.y * a;
  PRECISE vec3 first = vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  PRECISE vec3 second = vec3(c, sign + n.y * n.y * a, -n.y);
  t = first;
  b = second;
}

// 1 - cos(a) from sin(a), for a in [0, pi/2], without cancellation.
FN float oneMinusCosFromSin(float s) {
  PRECISE float s2 = s * s;
  PRECISE float h = s2 / (1.0f + sqrt(max(1.0f - s2, 0.0f)));
  return h;
}

// The three-term Sellmeier index at a wavelength (nm): n^2 = 1 +
// sum_i b_i l^2 / (l^2 - c_i), l in um. A constant index (every c zero)
// exactly, without the float rounding of b l^2 / l^2: no dispersion, as
// colour from the bins assumes. The host keeps poles out of the spectrum.
FN float sellmeierIndexAt(vec3 b, vec3 c, float lambda) {
  if (c.x == 0.0f && c.y == 0.0f && c.z == 0.0f) {
    PRECISE float constant = 1.0f + b.x + b.y + b.z;
    return sqrt(constant);
  }
  PRECISE float l = lambda * 0.001f;
  PRECISE float l2 = l * l;
  PRECISE float n2 = 1.0f + b.x * l2 / (l2 - c.x) + b.y * l2 / (l2 - c.y) + b.z * l2 / (l2 - c.z);
  return sqrt(n2);
}

// Unpolarised Fresnel reflectance for eta = n_incident / n_transmitted.
FN float fresnelDielectric(float cosIncident, float cosTransmitted, float eta) {
  PRECISE float rs = (eta * cosIncident - cosTransmitted) / (eta * cosIncident + cosTransmitted);
  PRECISE float rp = (cosIncident - eta * cosTransmitted) / (cosIncident + eta * cosTransmitted);
  PRECISE float f = 0.5f * (rs * rs + rp * rp);
  return f;
}

// Angular slack added to every aimed cone (radians, as a sine): covers the
// float rounding of cone axes and directions (a few 1e-8), so the cone
// always holds every direction that can be counted.
#define SPECTRACE_AIM_SLACK 4.0e-7f

#endif  // SPECTRACE_BEAM_MATH_H
