#include "colour/colour.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace spectrace {
namespace {

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

// Trapezoid integral of a 1 nm CMF column over its nodes in [lo, hi]
// (integers inside the table): Σ over segments of (y_i + y_{i+1})/2.
double trapezoid1nm(const Observer& o, const std::vector<double>& y, double lo, double hi) {
  double s = 0.0;
  for (size_t i = 0; i + 1 < o.lambdaNm.size(); ++i)
    if (o.lambdaNm[i] >= lo && o.lambdaNm[i + 1] <= hi) s += 0.5 * (y[i] + y[i + 1]);
  return s;
}

// ---------------------------------------------------------------- observers

TEST(Observer, TablesMatchCieValidationSums) {
  const Observer& o = cie1931Observer();
  EXPECT_EQ(o.name, "CIE1931_2");
  ASSERT_EQ(o.lambdaNm.size(), 471u);
  EXPECT_EQ(o.lambdaNm.front(), 360.0);
  EXPECT_EQ(o.lambdaNm.back(), 830.0);
  // Sums of 471 values of ~1 in double: rounding ~1e-14; the README gives
  // 15–16 significant digits. 1e-9 catches any lost or altered row.
  EXPECT_NEAR(sum(o.xbar), 106.865469489595, 1e-9);
  EXPECT_NEAR(sum(o.ybar), 106.8569171011719, 1e-9);
  EXPECT_NEAR(sum(o.zbar), 106.892251278636, 1e-9);
  const Observer& t = cie1964Observer();
  EXPECT_EQ(t.name, "CIE1964_10");
  ASSERT_EQ(t.lambdaNm.size(), 471u);
  EXPECT_NEAR(sum(t.xbar), 116.648519508908, 1e-9);
  EXPECT_NEAR(sum(t.ybar), 116.661877102312, 1e-9);
  EXPECT_NEAR(sum(t.zbar), 116.673980514647, 1e-9);
}

TEST(Observer, PeaksAndLookup) {
  const Observer& o = cie1931Observer();
  EXPECT_EQ(cmfAt(o, 555.0)[1], 1.0);  // exactly 1 as published
  EXPECT_EQ(cmfAt(cie1964Observer(), 557.0)[1], 1.0);
  EXPECT_EQ(*std::max_element(o.ybar.begin(), o.ybar.end()), 1.0);
  EXPECT_EQ(cmfAt(o, 359.9)[1], 0.0);
  EXPECT_EQ(cmfAt(o, 830.1)[0], 0.0);
  // Midway between two nodes: the mean (rounding ~1e-17 on values ≤ 2).
  EXPECT_NEAR(cmfAt(o, 555.5)[0], 0.5 * (o.xbar[195] + o.xbar[196]), 1e-16);
  EXPECT_EQ(&observerByName("CIE1931_2"), &o);
  EXPECT_EQ(&observerByName("CIE1964_10"), &cie1964Observer());
  EXPECT_THROW(observerByName("CIE2006_2"), std::invalid_argument);
}

// ---------------------------------------------------------------- bins

TEST(ColourBins, OneNmBinsCentredOnNodesMatchDirectTrapezoid) {
  const Observer& o = cie1931Observer();
  const auto w = binAveragedCmf(o, 359.5, 830.5, 471);
  ASSERT_EQ(w.size(), 471u);
  const std::array<const std::vector<double>*, 3> cols{&o.xbar, &o.ybar, &o.zbar};
  for (size_t i = 0; i < 471; ++i)
    for (int c = 0; c < 3; ++c) {
      const auto& y = *cols[c];
      // Trapezoid on [λ−½, λ] and [λ, λ+½] with the half-node values
      // (y_{i±1}+y_i)/2: (y_{i-1} + 6y_i + y_{i+1})/8. Outside the table the
      // CMF is zero, so the end bins keep only their inner half, (3y_0+y_1)/8.
      double expected;
      if (i == 0)
        expected = (3 * y[0] + y[1]) / 8;
      else if (i == 470)
        expected = (y[469] + 3 * y[470]) / 8;
      else
        expected = (y[i - 1] + 6 * y[i] + y[i + 1]) / 8;
      // Values ≤ 2, a handful of operations: 1e-15 absolute.
      EXPECT_NEAR(w[i][c], expected, 1e-15) << i << " " << c;
    }
}

TEST(ColourBins, AlignedBinsMatchTrapezoidAndBinsOutsideTheTableAreZero) {
  const Observer& o = cie1931Observer();
  // Six 100 nm bins over 300–900: the first covers the table only from 360,
  // the last only up to 830.
  const auto w = binAveragedCmf(o, 300, 900, 6);
  const double edges[] = {300, 400, 500, 600, 700, 800, 900};
  for (int b = 0; b < 6; ++b) {
    const double expected = trapezoid1nm(o, o.ybar, edges[b], edges[b + 1]) / 100.0;
    EXPECT_NEAR(w[b][1], expected, 1e-14) << b;  // sums of ≤100 terms ≤ 1
  }
  for (const auto& v : binAveragedCmf(o, 200, 359, 3)) EXPECT_EQ(v[1], 0.0);
  for (const auto& v : binAveragedCmf(o, 831, 900, 3)) EXPECT_EQ(v[1], 0.0);
}

TEST(ColourBins, BinSumTimesWidthIsCmfIntegral) {
  for (const Observer* o : {&cie1931Observer(), &cie1964Observer()}) {
    const std::array<const std::vector<double>*, 3> cols{&o->xbar, &o->ybar, &o->zbar};
    struct Case { double lo, hi; int bins; };
    for (const Case& k : {Case{359.5, 830.5, 471}, Case{383.3, 777.7, 37}, Case{300, 900, 7}, Case{360, 830, 1},
                          Case{100, 1000, 1000}}) {
      const auto w = binAveragedCmf(*o, k.lo, k.hi, k.bins);
      const double width = (k.hi - k.lo) / k.bins;
      for (int c = 0; c < 3; ++c) {
        double s = 0.0;
        for (const auto& v : w) s += v[c] * width;
        // Inside [lo, hi] the whole table is covered except for Case 2,
        // whose exact share is the trapezoid inside plus the cut pieces.
        const double full = trapezoid1nm(*o, *cols[c], 0, 1e9);
        if (k.lo <= 360 && k.hi >= 830) {
          EXPECT_NEAR(s / full, 1.0, 1e-13) << o->name << " " << k.bins << " " << c;  // ~1000 terms
        } else {
          // 383.3–777.7: trapezoid over 384..777 plus two linear pieces.
          const auto& y = *cols[c];
          const auto at = [&](double l) { return cmfAt(*o, l)[size_t(c)]; };
          const double inner = trapezoid1nm(*o, y, 384, 777);
          const double cut = 0.5 * 0.7 * (at(383.3) + at(384)) + 0.5 * 0.7 * (at(777) + at(777.7));
          EXPECT_NEAR(s / (inner + cut), 1.0, 1e-13) << o->name << " " << c;
        }
      }
    }
  }
}

TEST(ColourBins, RejectsBadArguments) {
  EXPECT_THROW(binAveragedCmf(cie1931Observer(), 400, 700, 0), std::invalid_argument);
  EXPECT_THROW(binAveragedCmf(cie1931Observer(), 700, 400, 3), std::invalid_argument);
}

// ---------------------------------------------------------------- XYZ

TEST(ColourXyz, LineGivesCmfAtItsWavelength) {
  const Observer& o = cie1931Observer();
  const auto xyz = spdToXyz(makeLineSpd(555.0), o);
  EXPECT_EQ(xyz[1], 1.0);
  EXPECT_EQ(xyz[0], cmfAt(o, 555.0)[0]);
  EXPECT_EQ(spdToXyzSummed(makeLineSpd(555.0), o)[1], 1.0);
  EXPECT_EQ(spdToXyz(makeLineSpd(900.0), o)[1], 0.0);
  EXPECT_EQ(spdToXyz(Spd{}, o)[1], 0.0);
}

TEST(ColourXyz, ConstantSpdGivesCmfIntegral) {
  const Observer& o = cie1931Observer();
  // Flat over 300–900: the product is the CMF itself, so exact integration
  // is the CMF's trapezoid integral (sum of 471 terms: 1e-13 relative).
  const auto xyz = spdToXyz(makeTabulatedSpd({300, 900}, {1, 1}), o);
  EXPECT_NEAR(xyz[0] / trapezoid1nm(o, o.xbar, 0, 1e9), 1.0, 1e-13);
  EXPECT_NEAR(xyz[1] / trapezoid1nm(o, o.ybar, 0, 1e9), 1.0, 1e-13);
  EXPECT_NEAR(xyz[2] / trapezoid1nm(o, o.zbar, 0, 1e9), 1.0, 1e-13);
}

TEST(ColourXyz, ExactProductIntegralMatchesFineQuadrature) {
  const Observer& o = cie1931Observer();
  // Nodes off the 1 nm grid; the product has kinks at 501, 502, ... which a
  // fine midpoint rule (h = 1e-5 nm) resolves to ~h² relative.
  const Spd s = makeTabulatedSpd({500.3, 501.7, 503.2}, {1.0, 2.0, 0.5});
  const auto xyz = spdToXyz(s, o);
  const int n = 290000;
  const double h = (503.2 - 500.3) / n;
  std::array<double, 3> ref{0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const double l = 500.3 + (i + 0.5) * h;
    const auto c = cmfAt(o, l);
    for (int k = 0; k < 3; ++k) ref[k] += h * s.evaluate(l) * c[k];
  }
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(xyz[k] / ref[k], 1.0, 1e-9) << k;
}

// ---------------------------------------------------------------- CIE data

struct Xy { double x, y; };

Xy xySummed(const char* name, const Observer& o = cie1931Observer()) {
  const auto c = chromaticity(spdToXyzSummed(*cieIlluminant(name), o));
  return {c[0], c[1]};
}
Xy xyExact(const char* name, const Observer& o = cie1931Observer()) {
  const auto c = chromaticity(spdToXyz(*cieIlluminant(name), o));
  return {c[0], c[1]};
}
// Plain summation at the SPD's own nodes (the 5 nm F tables), as CIE 015
// tabulates their chromaticities.
Xy xyAtSpdNodes(const char* name) {
  const Spd s = *cieIlluminant(name);
  std::array<double, 3> xyz{0, 0, 0};
  for (size_t i = 0; i < s.lambdaNm.size(); ++i) {
    const auto c = cmfAt(cie1931Observer(), s.lambdaNm[i]);
    for (int k = 0; k < 3; ++k) xyz[k] += s.value[i] * c[k];
  }
  const auto c = chromaticity(xyz);
  return {c[0], c[1]};
}

TEST(CieChromaticity, DaylightAndAMatchPublishedValues) {
  // CIE 015:2004 Table T.3, 5 decimals. The published values are computed
  // with other procedures/ranges, so allow one unit in the 5th decimal (the
  // README's own summation gives x = 0.31273 for D65).
  const Xy d65 = xySummed("D65");
  EXPECT_NEAR(d65.x, 0.31271, 5e-5);
  EXPECT_NEAR(d65.y, 0.32902, 5e-5);
  const Xy a = xySummed("A");
  EXPECT_NEAR(a.x, 0.44757, 5e-5);
  EXPECT_NEAR(a.y, 0.40745, 5e-5);
  const Xy d50 = xySummed("D50");
  EXPECT_NEAR(d50.x, 0.34567, 5e-5);
  EXPECT_NEAR(d50.y, 0.35850, 5e-5);
  // The README's values for exactly this summation, rounded to 5 decimals.
  EXPECT_NEAR(d65.x, 0.31273, 5e-6);
  EXPECT_NEAR(d65.y, 0.32902, 5e-6);
  EXPECT_NEAR(a.x, 0.44757, 5e-6);
  EXPECT_NEAR(a.y, 0.40744, 5e-6);
  // D65 white at Y = 100 (README, 3 decimals).
  const auto w = spdToXyzSummed(*cieIlluminant("D65"), cie1931Observer());
  EXPECT_NEAR(100 * w[0] / w[1], 95.047, 5e-4);
  EXPECT_NEAR(100 * w[2] / w[1], 108.883, 5e-4);
  // 10° observer: CIE 015 D65 (x10, y10) = (0.31382, 0.33100).
  const Xy d65t = xySummed("D65", cie1964Observer());
  EXPECT_NEAR(d65t.x, 0.31382, 5e-5);
  EXPECT_NEAR(d65t.y, 0.33100, 5e-5);
}

TEST(CieChromaticity, FluorescentMatchCie015) {
  struct Case { const char* name; double x4, y4, x5, y5, xq, yq; };
  // x4,y4: CIE 015 (4 decimals); x5,y5: README's 5 nm summation;
  // xq,yq: the often-quoted values from 1 nm interpolation then summation.
  for (const Case& c : {Case{"F2", 0.3721, 0.3751, 0.37207, 0.37512, 0.37208, 0.37529},
                        Case{"F7", 0.3129, 0.3292, 0.31285, 0.32917, 0.31292, 0.32933},
                        Case{"F11", 0.3805, 0.3769, 0.38054, 0.37692, 0.38052, 0.37713}}) {
    const Xy n = xyAtSpdNodes(c.name);
    EXPECT_NEAR(n.x, c.x4, 5e-5) << c.name;  // half a unit of the 4th decimal
    EXPECT_NEAR(n.y, c.y4, 5e-5) << c.name;
    EXPECT_NEAR(n.x, c.x5, 5e-6) << c.name;  // half a unit of the 5th decimal
    EXPECT_NEAR(n.y, c.y5, 5e-6) << c.name;
    // spdToXyzSummed interpolates the 5 nm table to the CMF's 1 nm nodes.
    const Xy s = xySummed(c.name);
    EXPECT_NEAR(s.x, c.xq, 5e-6) << c.name;
    EXPECT_NEAR(s.y, c.yq, 5e-6) << c.name;
  }
}

TEST(CieChromaticity, ExactIntegrationAgreesWithSummation) {
  // Both treat the data as piecewise linear; they differ by the trapezoid
  // bias of the product (h²/12·Σ f'g'), measured at ≤ 1.8e-5 in x, y
  // (largest for the spiky 5 nm F tables); 5e-5 leaves margin.
  for (const char* n : {"D65", "A", "D50", "F2", "F7", "F11", "LED-B3", "LED-RGB1"}) {
    const Xy s = xySummed(n), e = xyExact(n);
    EXPECT_NEAR(e.x, s.x, 5e-5) << n;
    EXPECT_NEAR(e.y, s.y, 5e-5) << n;
  }
  // And in magnitude: Y agrees to the same order.
  const auto ys = spdToXyzSummed(*cieIlluminant("D65"), cie1931Observer())[1];
  const auto ye = spdToXyz(*cieIlluminant("D65"), cie1931Observer())[1];
  EXPECT_NEAR(ye / ys, 1.0, 1e-4);
}

// ---------------------------------------------------------------- matrices

TEST(ColourMatrix, SrgbMatchesPublishedMatrix) {
  // IEC 61966-2-1 primaries with D65 (0.3127, 0.3290), as tabulated by
  // colour-science (10 decimals, row-major: rgb_r = row 0 · xyz).
  const double expected[3][3] = {{3.2409699419, -1.5373831776, -0.4986107603},
                                 {-0.9692436363, 1.8759675015, 0.0415550574},
                                 {0.0556300797, -0.2039769589, 1.0569715142}};
  const glm::dmat3 m = xyzToLinearSrgb();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      // glm is column-major: m[column][row]. 1e-9: the published digits are
      // rounded to 5e-11 and our derivation is double (≈1e-15).
      EXPECT_NEAR(m[c][r], expected[r][c], 1e-9) << "row " << r << " col " << c;
}

TEST(ColourMatrix, WhiteMapsToOneAndPrimariesToAxes) {
  const glm::dmat3 m = xyzToLinearSrgb();
  const glm::dvec3 white = m * glm::dvec3(0.3127 / 0.3290, 1.0, (1 - 0.3127 - 0.3290) / 0.3290);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(white[i], 1.0, 1e-14);  // double rounding
  // The red primary's XYZ maps onto the R axis.
  const glm::dvec3 red = m * glm::dvec3(0.64 / 0.33, 1.0, (1 - 0.64 - 0.33) / 0.33);
  EXPECT_GT(red[0], 0.0);
  EXPECT_NEAR(red[1], 0.0, 1e-14);
  EXPECT_NEAR(red[2], 0.0, 1e-14);
  EXPECT_THROW(xyzToRgbFromPrimaries({0.64, 0.33}, {0.3, 0.6}, {0.15, 0.0}, {0.3127, 0.329}), std::invalid_argument);
  EXPECT_THROW(xyzToRgbFromPrimaries({0.1, 0.1}, {0.2, 0.2}, {0.3, 0.3}, {0.3127, 0.329}), std::invalid_argument);
}

TEST(ColourMatrix, ChromaticityOfBlackIsZero) {
  const auto c = chromaticity({0, 0, 0});
  EXPECT_EQ(c[0], 0.0);
  EXPECT_EQ(c[1], 0.0);
}

}  // namespace
}  // namespace spectrace
