#pragma once
// Philox4x32-10 (philox.h) for a run of consecutive beam indices of one
// block at once: each round is the same integer work on every lane, done 8
// lanes at a time with AVX2 where the CPU has it (checked at run time). The
// words are those of philoxWords bit for bit (philox_test), so the CPU
// reference draws the same beams.
#include <cstdint>

namespace spectrace {

inline constexpr uint32_t kPhiloxLanes = 64;

// Words [w][lane] of beams firstIndex + lane (lane < kPhiloxLanes).
struct PhiloxLanes {
  alignas(64) uint32_t words[4][kPhiloxLanes];
};

void philoxLanes(uint64_t seed, uint64_t firstIndex, uint32_t block, PhiloxLanes& out);
// The same without SIMD (what runs on a CPU without AVX2), for the tests.
void philoxLanesWithoutSimd(uint64_t seed, uint64_t firstIndex, uint32_t block, PhiloxLanes& out);

}  // namespace spectrace
