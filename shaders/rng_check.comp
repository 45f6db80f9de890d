#version 460
// Writes Philox words for a range of beam indices, so tests can compare the
// GPU stream with the CPU's word for word.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_scalar_block_layout : require
#include "device_shared.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;
layout(set = 0, binding = kBindingRngWords, scalar) writeonly buffer Words { uvec4 words[]; };
layout(push_constant, scalar) uniform PushBlock { RngCheckPush push; };

#include "philox.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  words[i] = philox4x32(push.seed, push.firstIndex + uint64_t(i), push.block);
}
