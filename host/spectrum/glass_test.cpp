#include "spectrum/glass.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace spectrace {
namespace {

constexpr double kDLineNm = 587.5618;  // helium d line

double indexOf(const SellmeierGlass& g, double lambdaNm) { return sellmeierIndex(g.b, g.cUm2, lambdaNm); }

TEST(Glass, DLineIndicesMatchTheCatalogue) {
  // SCHOTT's nd to 5 decimals; fused silica's commonly quoted 1.4585
  // (Malitson's formula gives 1.45846).
  const struct {
    const char* name;
    double nd;
  } checks[] = {{"N-BK7", 1.5168}, {"N-SF11", 1.78472}, {"F2", 1.62004}, {"fused_silica", 1.4585}};
  for (const auto& c : checks) {
    const SellmeierGlass* g = glassNamed(c.name);
    ASSERT_NE(g, nullptr) << c.name;
    EXPECT_EQ(g->name, c.name);
    EXPECT_NEAR(indexOf(*g, kDLineNm), c.nd, 5e-5) << c.name;
  }
}

TEST(Glass, DispersionIsNormalAcrossTheVisible) {
  ASSERT_GE(glassNames().size(), 4u);
  for (const std::string& name : glassNames()) {
    const SellmeierGlass* g = glassNamed(name);
    ASSERT_NE(g, nullptr) << name;
    double previous = indexOf(*g, 400.0);
    ASSERT_TRUE(std::isfinite(previous) && previous > 1.0) << name;
    for (double lambda = 405.0; lambda <= 700.0; lambda += 5.0) {
      const double n = indexOf(*g, lambda);
      EXPECT_LT(n, previous) << name << " at " << lambda << " nm";
      previous = n;
    }
  }
}

TEST(Glass, UnknownNameIsNull) {
  EXPECT_EQ(glassNamed("BK7-typo"), nullptr);
  EXPECT_EQ(glassNamed("n-bk7"), nullptr);  // exact match, case included
  EXPECT_EQ(glassNamed(""), nullptr);
}

TEST(Glass, IndexIsNaNWhereTheFormulaHasNone) {
  const SellmeierGlass* g = glassNamed("N-BK7");
  ASSERT_NE(g, nullptr);
  // Just below the first UV pole the first term is large and negative: n^2 < 0.
  const double poleNm = std::sqrt(g->cUm2[0]) * 1e3;
  EXPECT_TRUE(std::isnan(indexOf(*g, poleNm * 0.999)));
  // Exactly at a pole (0.5 um, C = 0.25 um^2).
  EXPECT_TRUE(std::isnan(sellmeierIndex({1.0, 0.0, 0.0}, {0.25, 0.0, 0.0}, 500.0)));
  EXPECT_TRUE(std::isnan(sellmeierIndex({1.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, 0.0)));  // 0/0
}

}  // namespace
}  // namespace spectrace
