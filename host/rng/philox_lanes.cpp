#include "rng/philox_lanes.h"

#include <immintrin.h>

namespace spectrace {
namespace {

// Random123's constants (philox4x32round, philox4x32bumpkey).
constexpr uint32_t kMultiplier0 = 0xD2511F53u, kMultiplier1 = 0xCD9E8D57u;
constexpr uint32_t kWeyl0 = 0x9E3779B9u, kWeyl1 = 0xBB67AE85u;

// The plain lanes: also what runs where AVX2 is missing.
void philoxLanesScalar(uint64_t seed, uint64_t firstIndex, uint32_t block, PhiloxLanes& out) {
  for (uint32_t lane = 0; lane < kPhiloxLanes; ++lane) {
    const uint64_t index = firstIndex + lane;
    uint32_t c0 = uint32_t(index), c1 = uint32_t(index >> 32), c2 = block, c3 = 0u;
    uint32_t key0 = uint32_t(seed), key1 = uint32_t(seed >> 32);
    for (int round = 0; round < 10; ++round) {
      const uint64_t product0 = uint64_t(kMultiplier0) * c0;
      const uint64_t product1 = uint64_t(kMultiplier1) * c2;
      c0 = uint32_t(product1 >> 32) ^ c1 ^ key0;
      c1 = uint32_t(product1);
      c2 = uint32_t(product0 >> 32) ^ c3 ^ key1;
      c3 = uint32_t(product0);
      key0 += kWeyl0;
      key1 += kWeyl1;
    }
    out.words[0][lane] = c0;
    out.words[1][lane] = c1;
    out.words[2][lane] = c2;
    out.words[3][lane] = c3;
  }
}

// High and low words of the 32x32-bit products of 8 lanes by `m`: even
// lanes from one widening multiply, odd lanes from another. (Written with
// intrinsics: GCC 12 vectorises the plain loop with a full 64x64-bit
// multiply, three products per lane, and gains almost nothing.)
__attribute__((target("avx2"))) inline void multiplyHiLo(__m256i c, __m256i m, __m256i& hi, __m256i& lo) {
  const __m256i even = _mm256_mul_epu32(c, m);
  const __m256i odd = _mm256_mul_epu32(_mm256_srli_epi64(c, 32), m);
  hi = _mm256_blend_epi32(_mm256_srli_epi64(even, 32), odd, 0b10101010);
  lo = _mm256_blend_epi32(even, _mm256_slli_epi64(odd, 32), 0b10101010);
}

// Four groups of 8 lanes per pass, so that each round's multiplies of one
// group overlap the others' (a round is a chain of about 8 cycles).
__attribute__((target("avx2"))) void philoxLanesAvx2(uint64_t seed, uint64_t firstIndex, uint32_t block,
                                                      PhiloxLanes& out) {
  constexpr uint32_t kGroups = 4;
  static_assert(kPhiloxLanes % (8 * kGroups) == 0);
  const __m256i m0 = _mm256_set1_epi32(int(kMultiplier0));
  const __m256i m1 = _mm256_set1_epi32(int(kMultiplier1));
  for (uint32_t base = 0; base < kPhiloxLanes; base += 8 * kGroups) {
    alignas(32) uint32_t low[8 * kGroups], high[8 * kGroups];
    for (uint32_t lane = 0; lane < 8 * kGroups; ++lane) {
      const uint64_t index = firstIndex + base + lane;
      low[lane] = uint32_t(index);
      high[lane] = uint32_t(index >> 32);
    }
    __m256i c0[kGroups], c1[kGroups], c2[kGroups], c3[kGroups];
    for (uint32_t g = 0; g < kGroups; ++g) {
      c0[g] = _mm256_load_si256(reinterpret_cast<const __m256i*>(low + 8 * g));
      c1[g] = _mm256_load_si256(reinterpret_cast<const __m256i*>(high + 8 * g));
      c2[g] = _mm256_set1_epi32(int(block));
      c3[g] = _mm256_setzero_si256();
    }
    uint32_t key0 = uint32_t(seed), key1 = uint32_t(seed >> 32);
    for (int round = 0; round < 10; ++round) {
      const __m256i k0 = _mm256_set1_epi32(int(key0)), k1 = _mm256_set1_epi32(int(key1));
      for (uint32_t g = 0; g < kGroups; ++g) {
        __m256i hi0, lo0, hi1, lo1;
        multiplyHiLo(c0[g], m0, hi0, lo0);
        multiplyHiLo(c2[g], m1, hi1, lo1);
        c0[g] = _mm256_xor_si256(_mm256_xor_si256(hi1, c1[g]), k0);
        c1[g] = lo1;
        c2[g] = _mm256_xor_si256(_mm256_xor_si256(hi0, c3[g]), k1);
        c3[g] = lo0;
      }
      key0 += kWeyl0;
      key1 += kWeyl1;
    }
    for (uint32_t g = 0; g < kGroups; ++g) {
      const uint32_t at = base + 8 * g;
      _mm256_store_si256(reinterpret_cast<__m256i*>(&out.words[0][at]), c0[g]);
      _mm256_store_si256(reinterpret_cast<__m256i*>(&out.words[1][at]), c1[g]);
      _mm256_store_si256(reinterpret_cast<__m256i*>(&out.words[2][at]), c2[g]);
      _mm256_store_si256(reinterpret_cast<__m256i*>(&out.words[3][at]), c3[g]);
    }
  }
}

}  // namespace

void philoxLanes(uint64_t seed, uint64_t firstIndex, uint32_t block, PhiloxLanes& out) {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) philoxLanesAvx2(seed, firstIndex, block, out);
  else philoxLanesScalar(seed, firstIndex, block, out);
}

void philoxLanesWithoutSimd(uint64_t seed, uint64_t firstIndex, uint32_t block, PhiloxLanes& out) {
  philoxLanesScalar(seed, firstIndex, block, out);
}

}  // namespace spectrace
