#include "spectrum/spd.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace spectrace {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Runs f, expects an SpdError whose message contains every one of `parts`.
void expectSpdError(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no SpdError thrown; expected one mentioning '" << parts.front() << "'";
  } catch (const SpdError& e) {
    const std::string msg = e.what();
    for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
  }
}

// Writes `text` to a fresh file under the gtest temp dir.
fs::path writeTemp(const std::string& name, const std::string& text) {
  const fs::path p = fs::path(testing::TempDir()) / ("spectrace_spd_test_" + name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// Gauss–Legendre nodes/weights on [-1, 1] (Newton on P_n), for reference
// integrals independent of the trapezoid rule under test.
struct GaussLegendre {
  std::vector<double> x, w;
  explicit GaussLegendre(int n) {
    for (int i = 1; i <= n; ++i) {
      double z = std::cos(std::numbers::pi * (i - 0.25) / (n + 0.5)), pp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p1 = 1.0, p2 = 0.0;
        for (int j = 1; j <= n; ++j) {
          const double p3 = p2;
          p2 = p1;
          p1 = ((2.0 * j - 1.0) * z * p2 - (j - 1.0) * p3) / j;
        }
        pp = n * (z * p1 - p2) / (z * z - 1.0);
        const double dz = p1 / pp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      x.push_back(z);
      w.push_back(2.0 / ((1.0 - z * z) * pp * pp));
    }
  }
  // Composite rule with `panels` equal panels on [a, b].
  double integrate(const std::function<double(double)>& f, double a, double b, int panels) const {
    double s = 0.0;
    const double h = (b - a) / panels;
    for (int p = 0; p < panels; ++p) {
      const double c = a + (p + 0.5) * h;
      for (size_t i = 0; i < x.size(); ++i) s += w[i] * 0.5 * h * f(c + 0.5 * h * x[i]);
    }
    return s;
  }
};

// CODATA 2018 (σ rounded as published, 10 significant digits).
constexpr double kSigmaSB = 5.670374419e-8;  // W·m⁻²·K⁻⁴
constexpr double kWienB = 2.897771955e-3;    // m·K

// ---------------------------------------------------------------- tables

TEST(SpdTable, IntegralIsExactTrapezoidAndEvaluateInterpolates) {
  const Spd s = makeTabulatedSpd({400.0, 410.0, 430.0}, {1.0, 3.0, 2.0});
  EXPECT_FALSE(s.isLine());
  // 10·(1+3)/2 + 20·(3+2)/2 = 20 + 50; all terms exact in binary.
  EXPECT_EQ(s.integral(), 70.0);
  EXPECT_EQ(s.fullIntegral, 70.0);
  EXPECT_EQ(s.evaluate(405.0), 2.0);
  EXPECT_EQ(s.evaluate(420.0), 2.5);
  EXPECT_EQ(s.evaluate(400.0), 1.0);
  EXPECT_EQ(s.evaluate(430.0), 2.0);
  EXPECT_EQ(s.evaluate(399.999), 0.0);
  EXPECT_EQ(s.evaluate(430.001), 0.0);
  EXPECT_EQ(s.evaluate(kNaN), 0.0);
}

TEST(SpdTable, ValuesNearTheDoubleRangeKeepTheirShapeAndAFiniteIntegral) {
  // 1e308 overflows the trapezoid's sum; only the shape matters, so the table
  // is scaled by an exact power of two.
  const Spd s = makeTabulatedSpd({400.0, 500.0, 600.0}, {1e308, 1.5e308, 0.5e308});
  ASSERT_TRUE(std::isfinite(s.fullIntegral));
  EXPECT_GT(s.fullIntegral, 0.0);
  EXPECT_EQ(s.value[1] / s.value[0], 1.5e308 / 1e308);
  EXPECT_EQ(s.value[2] / s.value[0], 0.5e308 / 1e308);
  // Ordinary tables are left exactly as given.
  EXPECT_EQ(makeTabulatedSpd({400.0, 410.0}, {3.0, 5.0}).value[1], 5.0);
}

TEST(SpdTable, RejectsInvalidTables) {
  expectSpdError([] { makeTabulatedSpd({400, 410, 405}, {1, 1, 1}); },
                 {"row 3", "strictly increasing", "405 nm after 410 nm"});
  expectSpdError([] { makeTabulatedSpd({400, 400}, {1, 1}); }, {"row 2", "strictly increasing"});
  expectSpdError([] { makeTabulatedSpd({400, 512}, {1, -0.3}); }, {"row 2", "at 512 nm is negative (-0.3)"});
  expectSpdError([] { makeTabulatedSpd({400, 410}, {kNaN, 1}); }, {"row 1", "non-finite value"});
  expectSpdError([] { makeTabulatedSpd({400, INFINITY}, {1, 1}); }, {"row 2", "non-finite wavelength"});
  expectSpdError([] { makeTabulatedSpd({-1, 410}, {1, 1}); }, {"row 1", "must be positive"});
  expectSpdError([] { makeTabulatedSpd({400}, {1}); }, {"at least 2 points", "got 1"});
  expectSpdError([] { makeTabulatedSpd({}, {}); }, {"at least 2 points"});
  expectSpdError([] { makeTabulatedSpd({400, 410}, {1}); }, {"2 wavelengths but 1 values"});
  expectSpdError([] { makeTabulatedSpd({400, 410, 420}, {0, 0, 0}); }, {"SPD has no power"});
}

// ---------------------------------------------------------------- lines

TEST(SpdLine, DiracLine) {
  const Spd s = makeLineSpd(589.0);
  ASSERT_TRUE(s.isLine());
  EXPECT_EQ(s.lambdaNm[0], 589.0);
  EXPECT_EQ(s.integral(), 1.0);
  EXPECT_EQ(s.fullIntegral, 1.0);
  EXPECT_EQ(s.evaluate(589.0), 0.0);  // a Dirac line has no density anywhere
}

TEST(SpdLine, GaussianLineHasRightWidthAndUnitPower) {
  const double c = 532.0, fwhm = 2.0;
  const Spd s = makeLineSpd(c, fwhm);
  ASSERT_EQ(s.lambdaNm.size(), 1201u);
  const double sigma = fwhm / (2.0 * std::sqrt(2.0 * std::log(2.0)));
  EXPECT_NEAR(s.lambdaNm.front(), c - 6 * sigma, 1e-12);  // nm, rounding of c + xσ
  EXPECT_NEAR(s.lambdaNm.back(), c + 6 * sigma, 1e-12);
  EXPECT_EQ(s.fullIntegral, s.integral());
  // The trapezoid rule on a Gaussian at σ/100 spacing is accurate far below
  // 1e-9; the ±6σ cut drops 2e-9 of the power.
  EXPECT_NEAR(s.integral(), 1.0, 1e-8);
  const double peak = s.evaluate(c);
  EXPECT_NEAR(peak, 1.0 / (sigma * std::sqrt(2 * std::numbers::pi)), 1e-12);
  // Half maximum at c ± FWHM/2; linear interpolation between nodes σ/100
  // apart is off by ≤ h²/8·|f''| ≈ 1e-5 of the peak.
  EXPECT_NEAR(s.evaluate(c - fwhm / 2) / peak, 0.5, 2e-5);
  EXPECT_NEAR(s.evaluate(c + fwhm / 2) / peak, 0.5, 2e-5);
}

TEST(SpdLine, RejectsBadParameters) {
  expectSpdError([] { makeLineSpd(0.0); }, {"centre"});
  expectSpdError([] { makeLineSpd(kNaN); }, {"centre"});
  expectSpdError([] { makeLineSpd(500.0, 0.0); }, {"FWHM"});
  expectSpdError([] { makeLineSpd(500.0, -1.0); }, {"FWHM"});
  expectSpdError([] { makeLineSpd(500.0, kNaN); }, {"FWHM"});
  expectSpdError([] { makeLineSpd(10.0, 100.0); }, {"below 0 nm"});
}

// ---------------------------------------------------------------- clipping

TEST(SpdClip, InsertsCutNodesAndKeepsFullIntegral) {
  const Spd s = makeTabulatedSpd({400, 500, 600, 700}, {0, 2, 2, 0});  // integral 100+200+100
  ASSERT_EQ(s.integral(), 400.0);
  const Spd c = s.clipped(450.0, 650.0);
  EXPECT_EQ(c.lambdaNm, (std::vector<double>{450, 500, 600, 650}));
  EXPECT_EQ(c.value, (std::vector<double>{1, 2, 2, 1}));
  EXPECT_EQ(c.integral(), 75.0 + 200.0 + 75.0);  // exact in binary
  EXPECT_EQ(c.fullIntegral, 400.0);
  // Complementary pieces add up to the whole (exact arithmetic here).
  EXPECT_EQ(s.clipped(0, 450).integral() + c.integral() + s.clipped(650, 1000).integral(), 400.0);
  // A range covering everything returns the same table.
  const Spd all = s.clipped(100, 1000);
  EXPECT_EQ(all.lambdaNm, s.lambdaNm);
  EXPECT_EQ(all.value, s.value);
  // A cut at a non-representable point: the share must be the analytic one.
  // ∫_400^{400+d} of 0.02(λ-400) = 0.01 d²; relative rounding ~1e-15.
  const double d = 12.345;
  EXPECT_NEAR(s.clipped(0, 400 + d).integral(), 0.01 * d * d, 1e-12);
}

TEST(SpdClip, EmptyWhenOutsideOrDegenerate) {
  const Spd s = makeTabulatedSpd({400, 500}, {1, 1});
  EXPECT_TRUE(s.clipped(600, 700).lambdaNm.empty());
  EXPECT_TRUE(s.clipped(300, 350).lambdaNm.empty());
  EXPECT_EQ(s.clipped(300, 350).integral(), 0.0);
  EXPECT_EQ(s.clipped(300, 350).fullIntegral, 100.0);
  // Touching at one point: zero width, must not turn into a one-node "line".
  EXPECT_TRUE(s.clipped(500, 600).lambdaNm.empty());
  EXPECT_TRUE(s.clipped(450, 440).lambdaNm.empty());
}

TEST(SpdClip, LinesAreKeptOrDropped) {
  const Spd l = makeLineSpd(546.1);
  const Spd in = l.clipped(380, 780);
  ASSERT_TRUE(in.isLine());
  EXPECT_EQ(in.integral(), 1.0);
  EXPECT_EQ(in.fullIntegral, 1.0);
  EXPECT_TRUE(l.clipped(380, 546.0).lambdaNm.empty());
  EXPECT_EQ(l.clipped(380, 546.0).integral(), 0.0);
  EXPECT_EQ(l.clipped(380, 546.0).fullIntegral, 1.0);
  EXPECT_TRUE(l.clipped(546.1, 546.1).isLine());  // inclusive bounds
}

// ---------------------------------------------------------------- CSV

TEST(SpdCsv, ReadsHeaderCommentsBlankLinesAndUnevenSpacing) {
  const fs::path p = writeTemp("ok.csv",
                               "# measured lamp\r\n"
                               "wavelength_nm, power\r\n"
                               "\r\n"
                               "400, 0   # first\r\n"
                               "401.5,3\r\n"
                               "  # a comment\n"
                               "410,+3e0\n"
                               "450,0");
  const Spd s = loadCsvSpd(p);
  EXPECT_EQ(s.lambdaNm, (std::vector<double>{400, 401.5, 410, 450}));
  EXPECT_EQ(s.value, (std::vector<double>{0, 3, 3, 0}));
  EXPECT_EQ(s.integral(), 2.25 + 25.5 + 60.0);
  EXPECT_EQ(s.fullIntegral, s.integral());
}

TEST(SpdCsv, ReadsHeaderlessFileAndNamedColumns) {
  const Spd a = loadCsvSpd(writeTemp("nohdr.csv", "500,1\n600,1\n"));
  EXPECT_EQ(a.integral(), 100.0);
  const fs::path multi = writeTemp("multi.csv", "nm,red,green\n500,1,0\n600,3,2\n");
  EXPECT_EQ(loadCsvSpd(multi, "red").integral(), 200.0);
  EXPECT_EQ(loadCsvSpd(multi, "green").integral(), 100.0);
}

TEST(SpdCsv, AByteOrderMarkDoesNotTurnTheFirstRowIntoAHeader) {
  const Spd s = loadCsvSpd(writeTemp("bom.csv", "\xEF\xBB\xBF" "500,1\n600,3\n"));
  EXPECT_EQ(s.lambdaNm, (std::vector<double>{500, 600}));
  EXPECT_EQ(s.integral(), 200.0);
  const Spd named = loadCsvSpd(writeTemp("bom_header.csv", "\xEF\xBB\xBF" "nm,value\n500,1\n600,3\n"), "value");
  EXPECT_EQ(named.integral(), 200.0);
}

// Spreadsheets quote fields (RFC 4180): "" is a literal quote, and a
// separator or '#' inside quotes is part of the field.
TEST(SpdCsv, ReadsQuotedHeaderAndFields) {
  const fs::path quoted = writeTemp("quoted.csv", "\"wavelength\",\"value\"\r\n\"500\",\"1\"\r\n600,\"3\"\r\n");
  EXPECT_EQ(loadCsvSpd(quoted, "value").integral(), 200.0);
  EXPECT_EQ(loadCsvSpd(quoted).integral(), 200.0);
  const fs::path numbers = writeTemp("quoted_numbers.csv", "\"500\", \"1.5\"  # a comment\n\"600\",\"+2.5e0\"\n");
  const Spd s = loadCsvSpd(numbers);
  EXPECT_EQ(s.lambdaNm, (std::vector<double>{500, 600}));
  EXPECT_EQ(s.value, (std::vector<double>{1.5, 2.5}));
  const fs::path names = writeTemp("quoted_names.csv",
                                   "nm,\"lamp, \"\"warm\"\"\",\"# of photons\"\n500,1,2\n600,3,4\n");
  EXPECT_EQ(loadCsvSpd(names, "lamp, \"warm\"").integral(), 200.0);
  EXPECT_EQ(loadCsvSpd(names, "# of photons").integral(), 300.0);
  expectSpdError([&] { loadCsvSpd(names, "blue"); }, {"columns are: lamp, \"warm\", # of photons"});
  const fs::path open = writeTemp("quote_open.csv", "nm,v\n500,\"1\n600,2\n");
  expectSpdError([&] { loadCsvSpd(open); }, {open.string() + ":2:", "field 2", "quote", "never closed"});
  const fs::path after = writeTemp("quote_after.csv", "nm,v\n500,\"1\"2\n600,2\n");
  expectSpdError([&] { loadCsvSpd(after); }, {after.string() + ":2:", "field 2", "after its closing quote"});
}

TEST(SpdCsv, ReadsTabAndSemicolonSeparatedFiles) {
  const fs::path tab = writeTemp("tab.tsv", "wavelength_nm\tpower\r\n# lamp\n500\t1\n550 \t 3  # spaced\n600\t3\n");
  const Spd t = loadCsvSpd(tab, "power");
  EXPECT_EQ(t.lambdaNm, (std::vector<double>{500, 550, 600}));
  EXPECT_EQ(t.value, (std::vector<double>{1, 3, 3}));
  const fs::path tabNoHdr = writeTemp("tab_nohdr.tsv", "500\t1\n600\t1\n");
  EXPECT_EQ(loadCsvSpd(tabNoHdr).integral(), 100.0);
  const fs::path tabRagged = writeTemp("tab_ragged.tsv", "nm\tv\n500\t1\n550\t\t3\n");
  expectSpdError([&] { loadCsvSpd(tabRagged); }, {tabRagged.string() + ":3:", "expected 2 tab-separated fields, got 3"});
  const fs::path semi = writeTemp("semi.csv", "\"nm\";\"red\";\"green\"\n500;1;0\n600;3;2\n");
  EXPECT_EQ(loadCsvSpd(semi, "red").integral(), 200.0);
  EXPECT_EQ(loadCsvSpd(semi, "green").integral(), 100.0);
  // A decimal comma in a semicolon file is not a number; the message says why.
  const fs::path decimalComma = writeTemp("semi_decimal_comma.csv", "nm;v\n500;1,5\n600;2\n");
  expectSpdError([&] { loadCsvSpd(decimalComma); },
                 {decimalComma.string() + ":2:", "'1,5' is not a number", "decimal comma"});
}

TEST(SpdCsv, AnUnclearOrChangingSeparatorIsNamedWithFileAndLine) {
  // Both ',' and ';' split the header and the first data row alike: which
  // one is meant is unclear.
  const fs::path mixed = writeTemp("mixed.csv", "# lamp\nnm,value;other\n500,1;2\n");
  expectSpdError([&] { loadCsvSpd(mixed); }, {mixed.string() + ":2:", "separator is unclear", "','", "';'"});
  const fs::path tabComma = writeTemp("tab_comma.csv", "500\t1,5\n600\t2\n");
  expectSpdError([&] { loadCsvSpd(tabComma); }, {tabComma.string() + ":1:", "separator", "','", "tab"});
  // A comma file keeps a ';' in a column name, and tabs that pad its commas.
  const fs::path semiName = writeTemp("semi_in_name.csv", "nm,power; W/nm\n500,1\n600,3\n");
  EXPECT_EQ(loadCsvSpd(semiName, "power; W/nm").integral(), 200.0);
  const fs::path tabPadded = writeTemp("tab_padded.csv", "nm,\tv\n500,\t1\n600,\t3\n");
  EXPECT_EQ(loadCsvSpd(tabPadded, "v").integral(), 200.0);
  // One separator per file: a later line with another is named.
  const fs::path changed = writeTemp("changed.csv", "nm\tv\n500\t1\n600;2\n");
  expectSpdError([&] { loadCsvSpd(changed); },
                 {changed.string() + ":3:", "expected 2 tab-separated fields, got 1", "';'", "line 1"});
  // A line with no separator at all says which ones it looked for.
  const fs::path spaces = writeTemp("spaces.csv", "500 1\n600 2\n");
  expectSpdError([&] { loadCsvSpd(spaces); }, {spaces.string() + ":1:", "',', tab or ';'"});
}

TEST(SpdCsv, ErrorsNameFileLineAndProblem) {
  const fs::path nonMono = writeTemp("nonmono.csv", "nm,v\n400,1\n410,1\n\n400,1\n");
  expectSpdError([&] { loadCsvSpd(nonMono); },
                 {nonMono.string() + ":5:", "strictly increasing", "400 nm after 410 nm"});
  const fs::path neg = writeTemp("neg.csv", "400,1\n# c\n512,-0.3\n");
  expectSpdError([&] { loadCsvSpd(neg); }, {neg.string() + ":3", "value at 512 nm is negative (-0.3)"});
  const fs::path nan = writeTemp("nan.csv", "nm,v\n400,1\n410,NaN\n");
  expectSpdError([&] { loadCsvSpd(nan); }, {nan.string() + ":3", "non-finite value"});
  const fs::path garbage = writeTemp("garbage.csv", "nm,v\n400,1\n410,1.2.3\n");
  expectSpdError([&] { loadCsvSpd(garbage); }, {garbage.string() + ":3:", "'1.2.3' is not a number"});
  const fs::path ragged = writeTemp("ragged.csv", "nm,v\n400,1\n410,1,2\n");
  expectSpdError([&] { loadCsvSpd(ragged); }, {ragged.string() + ":3:", "expected 2", "got 3"});
  const fs::path one = writeTemp("one.csv", "nm,v\n400,1\n");
  expectSpdError([&] { loadCsvSpd(one); }, {one.string(), "at least 2 points"});
  const fs::path empty = writeTemp("empty.csv", "# nothing\nnm,v\n");
  expectSpdError([&] { loadCsvSpd(empty); }, {empty.string(), "no data rows"});
  const fs::path zero = writeTemp("zero.csv", "400,0\n500,0\n");
  expectSpdError([&] { loadCsvSpd(zero); }, {zero.string(), "SPD has no power"});
  const fs::path missing = fs::path(testing::TempDir()) / "spectrace_no_such_file.csv";
  expectSpdError([&] { loadCsvSpd(missing); }, {"not found", missing.string()});
  const fs::path multi = writeTemp("multi2.csv", "nm,red,green\n500,1,0\n600,3,2\n");
  expectSpdError([&] { loadCsvSpd(multi, "blue"); },
                 {multi.string(), "column 'blue' not found", "columns are: red, green"});
  expectSpdError([&] { loadCsvSpd(multi); }, {multi.string(), "2 value columns", "red, green"});
  const fs::path multiNoHdr = writeTemp("multi3.csv", "500,1,0\n600,3,2\n");
  expectSpdError([&] { loadCsvSpd(multiNoHdr, "red"); }, {multiNoHdr.string(), "no header"});
  // A bad value in a column that is not used does not matter...
  const fs::path partly = writeTemp("partly.csv", "nm,a,b\n500,1,-1\n600,1,nan\n");
  EXPECT_EQ(loadCsvSpd(partly, "a").integral(), 100.0);
  // ...but in the chosen one it does, and the message names the column.
  expectSpdError([&] { loadCsvSpd(partly, "b"); }, {partly.string() + ":2", "column 'b'", "negative"});
}

// ---------------------------------------------------------------- Planck

// Reference: π∫B dλ over 50 nm .. 1 mm in log λ (so that panels follow the
// curve), 16-point Gauss–Legendre on 400 panels.
double planckIntegral(double kelvin, double lo, double hi) {
  static const GaussLegendre gl(16);
  return gl.integrate([&](double u) { const double l = std::exp(u); return planckRadiance(l, kelvin) * l; },
                      std::log(lo), std::log(hi), 400);
}

TEST(Planck, StefanBoltzmann) {
  for (double t : {2700.0, 6500.0}) {
    const double exitance = std::numbers::pi * planckIntegral(t, 50.0, 1e6);
    // Missing tails: below 50 nm e^-44 of nothing; above 1 mm the
    // Rayleigh–Jeans tail is (15/π⁴)·x³/3 ≈ 1e-8 (x = hc/λkT ≤ 5.3e-3).
    // σ is published to 10 digits (5e-11). So 1e-7 is a safe, sharp bound.
    EXPECT_NEAR(exitance / (kSigmaSB * std::pow(t, 4)), 1.0, 1e-7) << t << " K";
  }
}

TEST(Planck, WienPeak) {
  for (double t : {2700.0, 6500.0}) {
    // Golden-section search for the maximum of B(λ) around b/T.
    double a = 0.5 * kWienB / t * 1e9, b = 2.0 * kWienB / t * 1e9;
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    while (b - a > 1e-9 * b) {
      const double c = b - g * (b - a), d = a + g * (b - a);
      if (planckRadiance(c, t) > planckRadiance(d, t))
        b = d;
      else
        a = c;
    }
    const double peakM = 0.5 * (a + b) * 1e-9;
    // The peak is flat (B ∝ 1 − O(δ²)), so doubles locate it to ~1e-8
    // relative; b is published to 10 digits. 1e-6 leaves margin both ways.
    EXPECT_NEAR(peakM * t / kWienB, 1.0, 1e-6) << t << " K";
  }
}

TEST(Planck, ReproducesCieIlluminantATable) {
  // CIE illuminant A is Planck's law with c2 = 1.435e7 nm·K at 2848 K,
  // normalised to 100 at 560 nm; with the exact c2 = hc/k that is the same
  // curve at T = 2848·c2/1.435e7 ≈ 2855.5 K. The CIE table is that formula
  // rounded to 6 significant digits, i.e. within 5e-6 relative.
  const double c2 = 6.62607015e-34 * 299792458.0 / 1.380649e-23 * 1e9;  // nm·K
  const double t = 2848.0 * c2 / 1.435e7;
  const Spd a = *cieIlluminant("A");
  ASSERT_EQ(a.lambdaNm.size(), 531u);
  double worst = 0.0;
  for (size_t i = 0; i < a.lambdaNm.size(); ++i) {
    const double expected = 100.0 * planckRadiance(a.lambdaNm[i], t) / planckRadiance(560.0, t);
    worst = std::max(worst, std::abs(a.value[i] / expected - 1.0));
  }
  EXPECT_LT(worst, 5e-6 + 1e-12);  // 6-digit rounding, + double rounding slack
  EXPECT_GT(worst, 1e-7);          // sanity: it really is the rounded table
}

TEST(Planck, RejectsBadArguments) {
  EXPECT_THROW(planckRadiance(0.0, 5000.0), SpdError);
  EXPECT_THROW(planckRadiance(500.0, -1.0), SpdError);
  EXPECT_THROW(planckRadiance(kNaN, 5000.0), SpdError);
  EXPECT_EQ(planckRadiance(500.0, 1.0), 0.0);  // underflows cleanly, no NaN
}

TEST(SpdBlackbody, TableIntegralMatchesExactPlanckIntegral) {
  static const GaussLegendre gl(16);
  struct Case { double t, lo, hi; };
  for (const Case& c : {Case{1000, 360, 830}, Case{2700, 360, 830}, Case{6500, 360, 830}, Case{20000, 360, 830},
                        Case{2700, 100, 5000}, Case{6500, 380.5, 381.25}}) {
    const Spd s = makeBlackbodySpd(c.t, c.lo, c.hi);
    EXPECT_EQ(s.lambdaNm.front(), c.lo);
    EXPECT_EQ(s.lambdaNm.back(), c.hi);
    // Reference in log λ, 16-point Gauss–Legendre on 2000 panels: ≲1e-14.
    const double exact = gl.integrate(
        [&](double u) { const double l = std::exp(u); return planckRadiance(l, c.t) * l; }, std::log(c.lo),
        std::log(c.hi), 2000);
    // The promise of makeBlackbodySpd: < 1e-6 relative.
    EXPECT_LT(std::abs(s.integral() / exact - 1.0), 1e-6) << c.t << " K [" << c.lo << ", " << c.hi << "]";
    // σT⁴/π with the exact-constant σ vs the 10-digit CODATA σ (5e-11).
    EXPECT_NEAR(s.fullIntegral / (kSigmaSB * std::pow(c.t, 4) / std::numbers::pi), 1.0, 1e-9);
    EXPECT_LT(s.integral(), s.fullIntegral);
    // Nodes follow the curve.
    for (size_t i = 0; i < s.lambdaNm.size(); i += 97)
      EXPECT_EQ(s.value[i], planckRadiance(s.lambdaNm[i], c.t));
  }
  // The visible share of a 6500 K blackbody is about 44 %: the in-range share
  // is integral()/fullIntegral.
  const Spd v = makeBlackbodySpd(6500, 380, 780);
  EXPECT_NEAR(v.integral() / v.fullIntegral, planckIntegral(6500, 380, 780) / planckIntegral(6500, 50, 1e6), 1e-6);
}

TEST(SpdBlackbody, RejectsBadParameters) {
  expectSpdError([] { makeBlackbodySpd(0.0, 360, 830); }, {"temperature"});
  expectSpdError([] { makeBlackbodySpd(kNaN, 360, 830); }, {"temperature"});
  expectSpdError([] { makeBlackbodySpd(5000, 830, 360); }, {"range"});
  expectSpdError([] { makeBlackbodySpd(5000, 0, 360); }, {"range"});
  expectSpdError([] { makeBlackbodySpd(5000, 360, INFINITY); }, {"range"});
  expectSpdError([] { makeBlackbodySpd(5.0, 360, 830); }, {"no power"});
}

// ---------------------------------------------------------------- CIE

TEST(CieIlluminant, AllNamesLoadWithPositivePower) {
  const std::vector<std::string> names = cieIlluminantNames();
  ASSERT_EQ(names.size(), 3u + 12u + 15u + 9u);
  EXPECT_EQ(names.front(), "A");
  EXPECT_EQ(names.back(), "LED-V2");
  for (const char* n : {"D50", "D65", "F1", "F12", "F3.1", "F3.15", "LED-B1", "LED-BH1", "LED-RGB1"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
  for (const auto& n : names) {
    const std::optional<Spd> s = cieIlluminant(n);
    ASSERT_TRUE(s) << n;
    EXPECT_GT(s->lambdaNm.size(), 80u) << n;
    EXPECT_GT(s->integral(), 0.0) << n;
    EXPECT_EQ(s->fullIntegral, s->integral()) << n;
  }
  EXPECT_FALSE(cieIlluminant("D66"));
  EXPECT_FALSE(cieIlluminant("a"));
}

TEST(CieIlluminant, TablesHaveDocumentedRangesAndNormalisation) {
  for (const char* n : {"A", "D50", "D65"}) {
    const Spd s = *cieIlluminant(n);
    EXPECT_EQ(s.lambdaNm.size(), 531u) << n;
    EXPECT_EQ(s.lambdaNm.front(), 300.0) << n;
    EXPECT_EQ(s.lambdaNm.back(), 830.0) << n;
    EXPECT_EQ(s.evaluate(560.0), 100.0) << n;  // exactly 100.0 as published
  }
  const Spd f2 = *cieIlluminant("F2");
  EXPECT_EQ(f2.lambdaNm.size(), 81u);
  EXPECT_EQ(f2.lambdaNm[1] - f2.lambdaNm[0], 5.0);
  EXPECT_EQ(cieIlluminant("LED-B3")->lambdaNm.size(), 401u);
  // F3.15 is on a much larger scale (peaks near 1417).
  const Spd f315 = *cieIlluminant("F3.15");
  EXPECT_GT(*std::max_element(f315.value.begin(), f315.value.end()), 1400.0);
}

}  // namespace
}  // namespace spectrace
