// A BVH node unpacked from the Vulkan trace's packed form
// (device_shared.h: PackedBvhNode). Every operation is exact: a step count
// below 2^24 converts to float without rounding, and a power-of-two scale
// in the normal range multiplies without rounding (the packer,
// host/compile/packed_bvh.cpp, keeps both so), so every device, with any
// rounding mode or denormal flushing, reads the same boxes, each one
// holding the float box it packs. A box test against a larger box meets
// every ray the smaller one meets, so the walk's hit is unchanged.
#ifndef SPECTRACE_PACKED_BVH_NODE_H
#define SPECTRACE_PACKED_BVH_NODE_H

// The four children's coordinates on one axis: (base + byte k) * scale.
FN vec4 unpackGridCoordinates(uint bytes, uint base, float scale) {
  ivec4 steps = ivec4((uvec4(bytes) >> uvec4(0u, 8u, 16u, 24u)) & uvec4(255u));
  PRECISE vec4 coordinates = vec4(ivec4(int(base)) + steps) * scale;
  return coordinates;
}

// 2^(e) from its biased exponent byte (e + 127, 1 to 254) at `shift`.
FN float unpackGridScale(uint exponents, uint shift) {
  return uintBitsToFloat(((exponents >> shift) & 255u) << 23u);
}

FN BvhNode unpackBvhNode(PackedBvhNode packed) {
  float scaleX = unpackGridScale(packed.grid.w, 0u);
  float scaleY = unpackGridScale(packed.grid.w, 8u);
  float scaleZ = unpackGridScale(packed.grid.w, 16u);
  BvhNode node;
  node.minX = unpackGridCoordinates(packed.boxesXY.x, packed.grid.x, scaleX);
  node.maxX = unpackGridCoordinates(packed.boxesXY.y, packed.grid.x, scaleX);
  node.minY = unpackGridCoordinates(packed.boxesXY.z, packed.grid.y, scaleY);
  node.maxY = unpackGridCoordinates(packed.boxesXY.w, packed.grid.y, scaleY);
  node.minZ = unpackGridCoordinates(packed.boxesZ.x, packed.grid.z, scaleZ);
  node.maxZ = unpackGridCoordinates(packed.boxesZ.y, packed.grid.z, scaleZ);
  node.child = packed.entries >> uvec4(kBvhCountBits);
  node.count = packed.entries & uvec4((1u << kBvhCountBits) - 1u);
  return node;
}

#endif  // SPECTRACE_PACKED_BVH_NODE_H
