#pragma once
// The one stream of beams: Philox4x32-10 keyed on the seed, with the 64-bit
// beam index and a dimension block as the counter. Integer only, so the CPU
// reference rebuilds any GPU beam bit for bit (shaders/philox.glsl is the
// GLSL twin; rng_test checks them against each other).
#include <array>
#include <cstdint>

namespace spectrace {

// Four 32-bit words for (seed, beamIndex, block). Counter = (index lo, index
// hi, block, 0), key = (seed lo, seed hi).
std::array<uint32_t, 4> philoxWords(uint64_t seed, uint64_t beamIndex, uint32_t block);

// The project's one integer-to-float conversion: (x >> 8) * 2^-24, which is
// exact in float32 and lies in [0, 1 - 2^-24].
constexpr float uniformFloat(uint32_t x) { return float(x >> 8) * (1.0f / 16777216.0f); }

// Two words as one 64-bit integer, low word first.
constexpr uint64_t joinWords(uint32_t lo, uint32_t hi) { return (uint64_t(hi) << 32) | lo; }

}  // namespace spectrace
