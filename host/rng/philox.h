#pragma once
// The one stream of beams: Philox4x32-10 keyed on the seed, with the 64-bit
// beam index and a dimension block as the counter. Integer only, so the CPU
// reference rebuilds any GPU beam bit for bit (shaders/philox.glsl is the
// GLSL twin; rng_test checks them against each other).
#include <array>
#include <cstdint>

#include <Random123/philox.h>
// Random123 also defines philox4x32(c, k) as a macro, which would rewrite
// the kernel's own philox4x32 (shaders/kernel_interface.h).
#undef philox4x32
#undef philox2x32
#undef philox4x64
#undef philox2x64

namespace spectrace {

// Four 32-bit words for (seed, beamIndex, block). Counter = (index lo, index
// hi, block, 0), key = (seed lo, seed hi). Inline: a beam draws two blocks,
// and inlined the compiler interleaves their independent rounds.
inline std::array<uint32_t, 4> philoxWords(uint64_t seed, uint64_t beamIndex, uint32_t block) {
  r123::Philox4x32_R<10> philox;
  const r123::Philox4x32_R<10>::ctr_type counter = {{uint32_t(beamIndex), uint32_t(beamIndex >> 32), block, 0u}};
  const r123::Philox4x32_R<10>::key_type key = {{uint32_t(seed), uint32_t(seed >> 32)}};
  const auto out = philox(counter, key);
  return {out[0], out[1], out[2], out[3]};
}

// The project's one integer-to-float conversion: (x >> 8) * 2^-24, which is
// exact in float32 and lies in [0, 1 - 2^-24].
constexpr float uniformFloat(uint32_t x) { return float(x >> 8) * (1.0f / 16777216.0f); }

// Two words as one 64-bit integer, low word first.
constexpr uint64_t joinWords(uint32_t lo, uint32_t hi) { return (uint64_t(hi) << 32) | lo; }

}  // namespace spectrace
