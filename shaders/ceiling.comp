#version 460
// The bench's ceiling (spectrace bench, "Profile"): the throughput scene's
// work with no exactness guarantees, to show how fast the device can go.
// A hash of the invocation for random numbers, the wavelength by a float
// CDF search, cosine-weighted disk emission, the sensor plane, one 32-bit
// atomic. Never used to render; host/backend/ceiling.cpp is its CPU twin.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_scalar_block_layout : require
#include "device_shared.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;
layout(set = 0, binding = kBindingCeilingCdf, scalar) readonly buffer CdfBlock { float cdf[]; };
layout(set = 0, binding = kBindingCeilingHistogram, scalar) buffer HistogramBlock { uint counts[]; };
layout(push_constant, scalar) uniform PushBlock { CeilingPush push; };

// PCG's output hash (O'Neill), a full-period permutation of 32-bit words.
uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
float uniformOf(uint word) { return float(word >> 8u) * (1.0 / 16777216.0); }

void main() {
  uint local = gl_GlobalInvocationID.y * push.beamsPerRow + gl_GlobalInvocationID.x;
  if (local >= push.beamCount) return;
  uint h0 = pcgHash(push.beamBase + local);
  uint h1 = pcgHash(h0);
  uint h2 = pcgHash(h1);
  uint h3 = pcgHash(h2);
  uint h4 = pcgHash(h3);

  // Wavelength: the last node with cdf <= u, then linear inside the interval.
  float u = uniformOf(h0);
  uint lo = 0u;
  uint hi = push.cdfCount - 1u;
  while (hi - lo > 1u) {
    uint mid = (lo + hi) >> 1u;
    if (cdf[mid] <= u) lo = mid; else hi = mid;
  }
  float width = cdf[lo + 1u] - cdf[lo];
  float t = width > 0.0 ? (u - cdf[lo]) / width : 0.0;
  float lambda = push.lambdaMin + (float(lo) + t) * push.nmPerNode;
  uint bin = min(uint(max((lambda - push.lambdaMin) * push.binsPerNm, 0.0)), push.bins - 1u);

  // Origin on the disk, direction cosine-weighted about -z.
  const float twoPi = 6.2831853;
  float r = push.diskRadius * sqrt(uniformOf(h1));
  float phi = twoPi * uniformOf(h2);
  vec3 origin = vec3(r * cos(phi), r * sin(phi), push.diskDistance);
  float sinSq = uniformOf(h3);
  float sinTheta = sqrt(sinSq);
  float cosTheta = sqrt(1.0 - sinSq);
  float psi = twoPi * uniformOf(h4);
  vec3 direction = vec3(sinTheta * cos(psi), sinTheta * sin(psi), -cosTheta);

  // The sensor plane z = 0.
  if (!(cosTheta > 0.0)) return;
  float s = origin.z / cosTheta;
  float hx = origin.x + s * direction.x;
  float hy = origin.y + s * direction.y;
  if (!(abs(hx) < push.sensorHalfSize) || !(abs(hy) < push.sensorHalfSize)) return;
  uint column = min(uint((hx + push.sensorHalfSize) * push.pixelsPerMetre), push.pixels - 1u);
  uint row = min(uint((push.sensorHalfSize - hy) * push.pixelsPerMetre), push.pixels - 1u);
  atomicAdd(counts[(row * push.pixels + column) * push.bins + bin], 1u);
}
