#pragma once
// The Vulkan trace's BVH nodes (device::PackedBvhNode, 64 bytes) from the
// four-wide tree's (device::BvhNode, 128 bytes). The CPU reference walks the
// full nodes, whose four float boxes its vector step reads as they are; the
// shader unpacks these (shaders/packed_bvh_node.h) into boxes that hold
// them, so both find the same hits: a larger box is met by every ray that
// meets the smaller one, and the walk's closest hit does not depend on
// which boxes it opens.
#include <span>
#include <vector>

#include "device_shared.h"

namespace spectrace {

// Each node packed: per axis, the finest power-of-two grid (at least
// 2^-126, so no coordinate is a denormal a device may flush) on which the
// children's union spans at most 255 steps and the base stays below 2^24 -
// 256 in magnitude; each child box rounded outwards onto it. The children
// and counts are unchanged. Throws std::invalid_argument for a node whose
// boxes are not finite, are inverted, or span beyond 2^126.
std::vector<device::PackedBvhNode> packBvhNodes(std::span<const device::BvhNode> nodes);

// The box the shader reads for `packed` (shaders/packed_bvh_node.h, the
// same text compiled here).
device::BvhNode unpackedBvhNode(const device::PackedBvhNode& packed);

}  // namespace spectrace
