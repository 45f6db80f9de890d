#version 460
// Histogram -> XYZ, linear sRGB and total irradiance, one invocation per
// pixel (the seed's Camera.getPixels()). Bin weights are 683 x the
// bin-averaged CMFs, integrated in double precision on the host.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_scalar_block_layout : require
#include "device_shared.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;
// Histogram buffers in use (device_shared.h); with one, no switch per read.
layout(constant_id = kSpecHistogramChunks) const uint histogramChunks = kMaxHistogramChunks + 1u;

layout(set = 0, binding = kBindingResolveConstants, scalar) readonly buffer ResolveConstantsBlock {
  ResolveConstants rc;
};
layout(set = 0, binding = kBindingBinWeights, scalar) readonly buffer BinWeightBlock {
  vec3 binWeights[];
};
layout(set = 0, binding = kBindingResolvedPixels, scalar) writeonly buffer ResolvedBlock {
  ResolvedPixel resolved[];
};
layout(set = 0, binding = kBindingResolveHistogram, scalar) readonly buffer HistogramChunk {
  uint64_t counts[];
} histogram[kMaxHistogramChunks];
layout(push_constant, scalar) uniform PushBlock {
  ResolvePush push;
};

uint64_t readCount(uint chunk, uint index) {
  if (histogramChunks == 1u) return histogram[0].counts[index];
  switch (chunk) {
    case 0u: return histogram[0].counts[index];
    case 1u: return histogram[1].counts[index];
    case 2u: return histogram[2].counts[index];
    case 3u: return histogram[3].counts[index];
    case 4u: return histogram[4].counts[index];
    case 5u: return histogram[5].counts[index];
    case 6u: return histogram[6].counts[index];
    default: return histogram[7].counts[index];
  }
}

void main() {
  uint slot = gl_GlobalInvocationID.x;
  if (slot >= push.pixelCount) return;
  uint pixel = push.firstPixel + slot;
  uint chunk = pixel / rc.pixelsPerChunk;
  uint base = (pixel - chunk * rc.pixelsPerChunk) * rc.countersPerPixel;
  uint64_t total = 0ul;  // exact
  uint64_t largest = 0ul;
  vec3 weighted = vec3(0.0);
  // llvmpipe (lavapipe) ends a shader loop after 65535 iterations in all
  // (nesting does not reset the count), which silently dropped the bins
  // past 65535. So the loop takes kResolveBinsPerIteration bins at a time
  // (vulkan_tracer.cpp checks that the largest spectrum stays under the
  // limit); the bins are still summed one by one, in order.
  uint b = 0u;
  uint whole = rc.bins - rc.bins % kResolveBinsPerIteration;
  for (; b < whole; b += kResolveBinsPerIteration) {
    // Written out, not an inner loop, which would count towards the limit
    // unless the compiler happened to unroll it.
    uint64_t c0 = readCount(chunk, base + b);
    uint64_t c1 = readCount(chunk, base + b + 1u);
    uint64_t c2 = readCount(chunk, base + b + 2u);
    uint64_t c3 = readCount(chunk, base + b + 3u);
    total += c0;
    largest = max(largest, c0);
    weighted += float(c0) * binWeights[b];
    total += c1;
    largest = max(largest, c1);
    weighted += float(c1) * binWeights[b + 1u];
    total += c2;
    largest = max(largest, c2);
    weighted += float(c2) * binWeights[b + 2u];
    total += c3;
    largest = max(largest, c3);
    weighted += float(c3) * binWeights[b + 3u];
  }
  for (; b < rc.bins; ++b) {
    uint64_t count = readCount(chunk, base + b);
    total += count;
    largest = max(largest, count);
    weighted += float(count) * binWeights[b];
  }
  vec3 xyz = weighted * rc.irradiancePerCount;
  if (rc.exactColour != 0u) {
    uint colour = base + colourCounterOffset(rc.bins);
    xyz = vec3(float(readCount(chunk, colour)), float(readCount(chunk, colour + 1u)),
               float(readCount(chunk, colour + 2u))) * rc.xyzPerColourUnit;
  }
  ResolvedPixel result;
  result.xyz = xyz;
  result.rgb = vec3(dot(rc.xyzToRgbRow0, xyz), dot(rc.xyzToRgbRow1, xyz), dot(rc.xyzToRgbRow2, xyz));
  result.irradiance = float(total) * rc.irradiancePerCount;
  result.padding0 = 0u;
  result.totalCount = total;
  result.squaredWeightCount =
      rc.squaredWeightOffset != 0u ? readCount(chunk, base + rc.squaredWeightOffset) : 0ul;
  result.largestCount = largest;
  resolved[slot] = result;
}
