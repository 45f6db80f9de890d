#version 460
// Histogram -> XYZ, linear sRGB and total irradiance, one invocation per
// pixel (the seed's Camera.getPixels()), through the one per-pixel resolve
// (resolve_pixel.h). Bin weights are 683 x the bin-averaged CMFs,
// integrated in double precision on the host.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_scalar_block_layout : require
#include "device_shared.h"
#include "kernel_lang.h"

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

// One pixel's counters for the shared resolve: its chunk and first counter.
struct StoredPixel {
  uint chunk;
  uint base;
};
#define RESOLVE_REAL float
#define RESOLVE_VEC3 vec3
#define RESOLVE_PIXEL StoredPixel
// Counter `counter` of a pixel (of its first word, and the second in a
// weighted film).
WideCount readCounter(StoredPixel pixel, uint counter) {
  WideCount w;
  if (rc.weighted != 0u) {
    w.low = readCount(pixel.chunk, pixel.base + 2u * counter);
    w.high = readCount(pixel.chunk, pixel.base + 2u * counter + 1u);
  } else {
    w.low = readCount(pixel.chunk, pixel.base + counter);
    w.high = 0ul;
  }
  return w;
}
WideCount resolveBinCount(StoredPixel pixel, uint bin) { return readCounter(pixel, bin); }
WideCount resolveColourSum(StoredPixel pixel, uint k) { return readCounter(pixel, rc.bins + k); }
vec3 resolveBinWeight(StoredPixel pixel, uint bin) { return binWeights[bin]; }
#include "resolve_pixel.h"

void main() {
  uint slot = gl_GlobalInvocationID.x;
  if (slot >= push.pixelCount) return;
  uint pixel = push.firstPixel + slot;
  StoredPixel stored;
  stored.chunk = pixel / rc.pixelsPerChunk;
  stored.base = (pixel - stored.chunk * rc.pixelsPerChunk) * rc.countersPerPixel;
  ResolveFactors factors;
  factors.bins = rc.bins;
  factors.exactColour = rc.exactColour != 0u;
  factors.irradiancePerCount = rc.irradiancePerCount;
  factors.xyzPerColourUnit = rc.xyzPerColourUnit;
  factors.xyzToRgbRow0 = rc.xyzToRgbRow0;
  factors.xyzToRgbRow1 = rc.xyzToRgbRow1;
  factors.xyzToRgbRow2 = rc.xyzToRgbRow2;
  PixelResolution sums = resolvePixel(stored, factors);
  ResolvedPixel result;
  result.xyz = sums.xyz;
  result.rgb = sums.rgb;
  result.irradiance = sums.irradiance;
  result.padding0 = 0u;
  result.totalCount = sums.total;
  result.squaredWeightCount.low = 0ul;
  result.squaredWeightCount.high = 0ul;
  if (rc.squaredWeightOffset != 0u) {  // only weighted films: two words
    result.squaredWeightCount.low = readCount(stored.chunk, stored.base + rc.squaredWeightOffset);
    result.squaredWeightCount.high = readCount(stored.chunk, stored.base + rc.squaredWeightOffset + 1u);
  }
  result.largestCount = sums.largest;
  resolved[slot] = result;
}
