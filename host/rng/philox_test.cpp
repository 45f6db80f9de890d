#include "rng/philox.h"

#include <gtest/gtest.h>

#include <Random123/philox.h>

namespace spectrace {
namespace {

// Known-answer vectors from the Random123 distribution (kat_vectors):
// philox4x32 10 rounds.
TEST(Philox, MatchesRandom123KnownAnswers) {
  r123::Philox4x32_R<10> philox;
  {
    auto out = philox({{0u, 0u, 0u, 0u}}, {{0u, 0u}});
    EXPECT_EQ(out[0], 0x6627e8d5u);
    EXPECT_EQ(out[1], 0xe169c58du);
    EXPECT_EQ(out[2], 0xbc57ac4cu);
    EXPECT_EQ(out[3], 0x9b00dbd8u);
  }
  {
    auto out = philox({{0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u}},
                      {{0xa4093822u, 0x299f31d0u}});
    EXPECT_EQ(out[0], 0xd16cfe09u);
    EXPECT_EQ(out[1], 0x94fdccebu);
    EXPECT_EQ(out[2], 0x5001e420u);
    EXPECT_EQ(out[3], 0x24126ea1u);
  }
  {
    auto out = philox({{0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu}},
                      {{0xffffffffu, 0xffffffffu}});
    EXPECT_EQ(out[0], 0x408f276du);
    EXPECT_EQ(out[1], 0x41c83b0eu);
    EXPECT_EQ(out[2], 0xa20bc7c6u);
    EXPECT_EQ(out[3], 0x6d5451fdu);
  }
}

TEST(Philox, CounterLayoutIsIndexLoHiBlockThenSeedKey) {
  const uint64_t seed = 0x0123456789abcdefull;
  const uint64_t index = 0xfedcba9876543210ull;
  r123::Philox4x32_R<10> philox;
  auto expected = philox({{0x76543210u, 0xfedcba98u, 7u, 0u}}, {{0x89abcdefu, 0x01234567u}});
  auto words = philoxWords(seed, index, 7);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(words[i], expected[i]);
}

TEST(Philox, StreamsPast2To32DoNotRepeat) {
  // Beam i and beam i + 2^32 must differ: the index's high word is counted.
  for (uint64_t i : {0ull, 1ull, 12345ull, (1ull << 32) - 1}) {
    EXPECT_NE(philoxWords(1, i, 0), philoxWords(1, i + (1ull << 32), 0)) << i;
  }
}

TEST(UniformFloat, IsExactAndBelowOne) {
  EXPECT_EQ(uniformFloat(0u), 0.0f);
  EXPECT_EQ(uniformFloat(0xffffffffu), 1.0f - 1.0f / 16777216.0f);
  EXPECT_LT(uniformFloat(0xffffffffu), 1.0f);
  EXPECT_EQ(uniformFloat(0x80000000u), 0.5f);
  EXPECT_EQ(uniformFloat(0x000000ffu), 0.0f);  // low 8 bits are dropped
}

}  // namespace
}  // namespace spectrace
