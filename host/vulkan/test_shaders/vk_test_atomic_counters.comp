#version 460
// vulkan_test: 64-bit atomic adds driven by push constants, a specialised
// workgroup size and an array of two storage buffers, with totals the host
// can predict exactly.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_scalar_block_layout : require

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint kSlots = 1;  // slots in counters[1]

layout(push_constant, scalar) uniform Push {
  uint64_t addend;     // added to counters[1].c[i % kSlots]
  uint invocations;    // invocations at or past this index do nothing
  uint rowInvocations; // invocations per row of workgroups (groupsX * local size)
} pc;

layout(set = 0, binding = 0, scalar) buffer Counters { uint64_t c[]; } counters[2];

void main() {
  const uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * pc.rowInvocations;
  if (i >= pc.invocations) return;
  atomicAdd(counters[0].c[0], uint64_t(1));       // count
  atomicAdd(counters[0].c[1], uint64_t(i));       // sum of indices
  atomicAdd(counters[0].c[2], uint64_t(1));       // preset near 2^32 - 1: must carry
  atomicAdd(counters[0].c[3], uint64_t(0xffffffffu)); // low-word overflow on every add
  atomicMax(counters[0].c[4], uint64_t(gl_LocalInvocationID.x + 1)); // = specialised local size
  atomicAdd(counters[1].c[i % kSlots], pc.addend);
}
