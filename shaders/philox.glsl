// Philox4x32-10 (Salmon et al., SC'11), the GLSL twin of Random123's
// r123::Philox4x32_R<10> used by the CPU reference (host/rng/philox.cpp).
// Counter = (index lo, index hi, block, 0), key = (seed lo, seed hi).
#ifndef SPECTRACE_PHILOX_GLSL
#define SPECTRACE_PHILOX_GLSL

uvec4 philoxRound(uvec4 counter, uvec2 key) {
  uint hi0;
  uint lo0;
  uint hi1;
  uint lo1;
  umulExtended(0xD2511F53u, counter.x, hi0, lo0);
  umulExtended(0xCD9E8D57u, counter.z, hi1, lo1);
  return uvec4(hi1 ^ counter.y ^ key.x, lo1, hi0 ^ counter.w ^ key.y, lo0);
}

uvec4 philox4x32(uint64_t seed, uint64_t index, uint block) {
  uvec4 counter = uvec4(uint(index), uint(index >> 32), block, 0u);
  uvec2 key = uvec2(uint(seed), uint(seed >> 32));
  counter = philoxRound(counter, key);
  for (int round = 1; round < 10; ++round) {
    key += uvec2(0x9E3779B9u, 0xBB67AE85u);
    counter = philoxRound(counter, key);
  }
  return counter;
}

#endif  // SPECTRACE_PHILOX_GLSL
