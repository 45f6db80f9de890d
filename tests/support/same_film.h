#pragma once
// Two films that must be the same bits: the same beams counted, and every
// bin count, colour sum and squared weight equal.
#include <gtest/gtest.h>

#include <string>

#include "film/spectral_histogram.h"

namespace spectrace::testing {

inline void expectSameFilm(const SpectralHistogram& a, const SpectralHistogram& b, const std::string& what) {
  EXPECT_EQ(a.countedBeams, b.countedBeams) << what;
  EXPECT_TRUE(a.counts() == b.counts()) << what << ": bin counts differ";
  EXPECT_TRUE(a.colourSums() == b.colourSums()) << what << ": colour sums differ";
  EXPECT_TRUE(a.squaredWeightSums() == b.squaredWeightSums()) << what << ": squared weights differ";
}

}  // namespace spectrace::testing
