// IES LM-63 reading: the header's factors, every Type C symmetry unfolded,
// bilinear intensity, the table's flux against closed forms and an
// independent quadrature, and each refusal naming the file and line.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "lights/photometric_file.h"

namespace spectrace {
namespace {

constexpr double kPi = std::numbers::pi;

// An LM-63-2002 file: header lines 1-3, TILT on line 4, the two number
// lines on 5 and 6, vertical angles on 7, horizontal on 8, then one line
// of candela values per horizontal angle from line 9.
std::string iesFile(const std::string& lumens, const std::string& multiplier, const std::string& vertical,
                    const std::string& horizontal, const std::vector<std::string>& rows, int verticalCount,
                    int horizontalCount, const std::string& tilt = "NONE", const std::string& type = "1") {
  std::string text = "IESNA:LM-63-2002\n[TEST] test\n[MANUFAC] spectrace\nTILT=" + tilt + "\n";
  text += fmt::format("1 {} {} {} {} {} 2 0.1 0.1 0.05\n", lumens, multiplier, verticalCount, horizontalCount, type);
  text += "0.9 1 42\n" + vertical + "\n" + horizontal + "\n";
  for (const std::string& row : rows) text += row + "\n";
  return text;
}

// I = 1000 cos(gamma) at 0, 10, ..., 90 degrees, rotationally symmetric.
std::string lambertianRow() {
  std::string row;
  for (int g = 0; g <= 90; g += 10) row += fmt::format("{:.17g} ", 1000.0 * std::cos(g * kPi / 180.0));
  return row;
}
const std::string kTenVertical = "0 10 20 30 40 50 60 70 80 90";

// The flux by the midpoint rule on a fine grid of the table's own
// intensity(): independent of tableLumens's closed forms.
double quadratureLumens(const PhotometricTable& t) {
  const int nc = 720, ng = 3600;
  double sum = 0.0;
  for (int j = 0; j < ng; ++j) {
    const double g = (j + 0.5) * 180.0 / ng;
    double ring = 0.0;
    for (int i = 0; i < nc; ++i) ring += t.intensity((i + 0.5) * 360.0 / nc, g);
    sum += ring * std::sin(g * kPi / 180.0);
  }
  return sum * (2.0 * kPi / nc) * (kPi / ng);
}

TEST(IesFile, ReadsTheHeaderAndAppliesItsFactors) {
  const PhotometricTable t = parseIes(iesFile("2500", "2", kTenVertical, "0", {lambertianRow()}, 10, 1), "lamp.ies");
  EXPECT_EQ(t.cDegrees, (std::vector<double>{0.0, 360.0}));
  EXPECT_EQ(t.gammaDegrees.size(), 10u);
  ASSERT_TRUE(t.ratedLumens);
  EXPECT_EQ(*t.ratedLumens, 2500.0);
  EXPECT_EQ(t.inputWatts, 42.0);
  // Multiplier 2 and ballast factor 0.9.
  EXPECT_DOUBLE_EQ(t.at(0, 0), 1800.0);
  EXPECT_DOUBLE_EQ(t.intensity(123.0, 30.0), 1800.0 * std::cos(kPi / 6.0));
  EXPECT_EQ(t.intensity(0.0, 95.0), 0.0);  // beyond the table: no light
  // Between nodes: linear in gamma.
  EXPECT_DOUBLE_EQ(t.intensity(7.0, 35.0), 0.5 * (t.at(0, 3) + t.at(0, 4)));
}

TEST(IesFile, AbsolutePhotometryHasNoRatedLumens) {
  const PhotometricTable t = parseIes(iesFile("-1", "1", kTenVertical, "0", {lambertianRow()}, 10, 1), "abs.ies");
  EXPECT_FALSE(t.ratedLumens);
}

TEST(IesFile, TableLumensIntegrateTheBilinearTable) {
  // A constant table over the whole sphere: 4 pi I exactly.
  const PhotometricTable uniform =
      parseIes(iesFile("-1", "1", "0 45 90 180", "0 90", {"7 7 7 7", "7 7 7 7"}, 4, 2), "uniform.ies");
  EXPECT_NEAR(uniform.tableLumens(), 4.0 * kPi * 7.0 * 0.9, 1e-12);
  // Lambertian downlight: near pi I0 (the bilinear table's chords lie under
  // the cosine: within 0.3% at 10-degree steps), and equal to a quadrature
  // of intensity() to its own accuracy.
  const PhotometricTable lambertian =
      parseIes(iesFile("-1", "1", kTenVertical, "0", {lambertianRow()}, 10, 1), "lambert.ies");
  const double i0 = 900.0;
  EXPECT_NEAR(lambertian.tableLumens(), kPi * i0, 3e-3 * kPi * i0);
  EXPECT_NEAR(lambertian.tableLumens(), quadratureLumens(lambertian), 1e-6 * kPi * i0);
}

TEST(IesFile, QuadrantSymmetryUnfolds) {
  const PhotometricTable t =
      parseIes(iesFile("1000", "1", "0 90", "0 45 90", {"10 1", "20 2", "30 3"}, 2, 3), "quadrant.ies");
  EXPECT_EQ(t.cDegrees, (std::vector<double>{0, 45, 90, 135, 180, 225, 270, 315, 360}));
  for (double c : {10.0, 45.0, 80.0}) {
    const double i = t.intensity(c, 0.0);
    EXPECT_DOUBLE_EQ(t.intensity(180.0 - c, 0.0), i) << c;
    EXPECT_DOUBLE_EQ(t.intensity(180.0 + c, 0.0), i) << c;
    EXPECT_DOUBLE_EQ(t.intensity(360.0 - c, 0.0), i) << c;
  }
  EXPECT_DOUBLE_EQ(t.intensity(45.0, 45.0), 0.9 * 11.0);
  EXPECT_NEAR(t.tableLumens(), quadratureLumens(t), 1e-6 * t.tableLumens());
}

TEST(IesFile, BilateralSymmetriesUnfold) {
  const PhotometricTable t =
      parseIes(iesFile("1000", "1", "0 90", "0 90 180", {"10 1", "20 2", "30 3"}, 2, 3), "bilateral.ies");
  EXPECT_EQ(t.cDegrees, (std::vector<double>{0, 90, 180, 270, 360}));
  EXPECT_DOUBLE_EQ(t.intensity(270.0, 0.0), 0.9 * 20.0);
  EXPECT_DOUBLE_EQ(t.intensity(300.0, 0.0), t.intensity(60.0, 0.0));
  // LM-63-1995's symmetry about the C90-C270 plane.
  const PhotometricTable old =
      parseIes(iesFile("1000", "1", "0 90", "90 180 270", {"10 1", "20 2", "30 3"}, 2, 3), "bilateral95.ies");
  EXPECT_EQ(old.cDegrees, (std::vector<double>{0, 90, 180, 270, 360}));
  EXPECT_DOUBLE_EQ(old.intensity(0.0, 0.0), 0.9 * 20.0);   // the image of C = 180
  EXPECT_DOUBLE_EQ(old.intensity(45.0, 0.0), old.intensity(135.0, 0.0));
  EXPECT_DOUBLE_EQ(old.intensity(315.0, 0.0), old.intensity(225.0, 0.0));
}

TEST(IesFile, NinetyToTwoSeventyWithout180WrapsAcrossZero) {
  // 90, 150, 210, 270: the images are 90-270 and 330-30 across 0, with no
  // column at 0 or 360 of their own; the table gets one, interpolated
  // between C 330 (the image of 210) and C 390 (that of 150), halfway.
  const PhotometricTable t =
      parseIes(iesFile("1000", "1", "0 90", "90 150 210 270", {"10 1", "20 2", "40 4", "30 3"}, 2, 4), "wrap.ies");
  EXPECT_EQ(t.cDegrees, (std::vector<double>{0, 30, 90, 150, 210, 270, 330, 360}));
  EXPECT_DOUBLE_EQ(t.intensity(0.0, 0.0), 0.9 * 30.0);
  EXPECT_DOUBLE_EQ(t.intensity(360.0, 0.0), 0.9 * 30.0);
  EXPECT_DOUBLE_EQ(t.intensity(15.0, 0.0), 0.9 * 25.0);  // a quarter of the way from 330 to 390
  EXPECT_NEAR(t.tableLumens(), quadratureLumens(t), 1e-6 * t.tableLumens());
}

TEST(IesFile, AnglesCloserThanAThousandthOfADegreeAreRefused) {
  try {
    parseIes(iesFile("1000", "1", "0 45 45.0005 90", "0", {"1 1 1 1"}, 4, 1), "close.ies");
    FAIL() << "accepted";
  } catch (const PhotometricFileError& e) {
    EXPECT_NE(std::string(e.what()).find("close.ies:7: vertical angle 3 of 4 is 45.0005, within 0.001 degrees"),
              std::string::npos)
        << e.what();
  }
}

TEST(IesFile, FullTableKeepsItsAsymmetry) {
  const PhotometricTable t = parseIes(
      iesFile("1000", "1", "0 90 180", "0 90 180 270 360", {"1 1 0", "2 2 0", "3 3 0", "4 4 0", "1 1 0"}, 3, 5),
      "asym.ies");
  EXPECT_EQ(t.cDegrees.size(), 5u);
  EXPECT_DOUBLE_EQ(t.intensity(45.0, 0.0), 0.9 * 1.5);
  EXPECT_DOUBLE_EQ(t.intensity(225.0, 45.0), 0.9 * 3.5);
  EXPECT_DOUBLE_EQ(t.intensity(-90.0, 0.0), 0.9 * 4.0);  // C modulo 360
  EXPECT_NEAR(t.tableLumens(), quadratureLumens(t), 1e-6 * t.tableLumens());
}

// Each refusal names the file and the line of the fault.
void expectRefused(const std::string& text, const std::string& fragment) {
  try {
    parseIes(text, "bad.ies");
    ADD_FAILURE() << "accepted a file that should fail with '" << fragment << "':\n" << text;
  } catch (const PhotometricFileError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(IesFile, RefusalsNameTheFileAndLine) {
  const std::vector<std::string> rows = {"10 1", "20 2", "30 3"};
  expectRefused(iesFile("1000", "1", "0 90", "0 45 90", {"10 1", "20 2", "30"}, 2, 3), "bad.ies:11: the file ends");
  expectRefused(iesFile("1000", "1", "0 90", "0 45 90", {"10 1", "20 2", "30 3 4 5"}, 2, 3),
                "bad.ies:11: 2 more numbers after the 3 x 2 candela values");
  expectRefused(iesFile("1000", "1", "0 50 40", "0 45 90", {"1 1 1", "2 2 2", "3 3 3"}, 3, 3),
                "bad.ies:7: vertical angle 3 of 3 is 40, not above the one before");
  expectRefused(iesFile("1000", "1", "0 90", "0 45 90", {"10 1", "20 -2", "30 3"}, 2, 3),
                "bad.ies:10: candela value -2 at horizontal angle 45, vertical angle 90 is negative");
  expectRefused(iesFile("1000", "1", "0 90", "0 45 90", rows, 2, 3, "INCLUDE"), "bad.ies:4: TILT=INCLUDE");
  expectRefused(iesFile("1000", "1", "0 90", "0 45 90", rows, 2, 3, "NONE", "2"), "bad.ies:5: photometric type is 2");
  expectRefused(iesFile("1000", "1", "0 90", "0 45 120", rows, 2, 3), "bad.ies:8: horizontal angles run from 0 to 120");
  expectRefused(iesFile("1000", "1", "0 60", "0 45 90", rows, 2, 3), "bad.ies:7: vertical angles run from 0 to 60");
  expectRefused(iesFile("0", "1", "0 90", "0 45 90", rows, 2, 3), "bad.ies:5: lumens per lamp is 0");
  expectRefused(iesFile("1000", "0", "0 90", "0 45 90", rows, 2, 3), "bad.ies:5: candela multiplier is 0");
  expectRefused(iesFile("1000", "1", "0 90", "0 4x5 90", rows, 2, 3), "bad.ies:8: '4x5' is not a number");
  expectRefused(iesFile("1000", "1", "0 90", "0 45 90", rows, 2, 2), "bad.ies:8: horizontal angles run from 0 to 45");
  expectRefused("IESNA:LM-63-2002\n[TEST] x\n", "bad.ies:2: no TILT= line");
}

TEST(IesFile, ReadsFilesAndNamesAMissingOne) {
  EXPECT_THROW(readIesFile("/nonexistent/lamp.ies"), PhotometricFileError);
  try {
    readIesFile("/nonexistent/lamp.ies");
  } catch (const PhotometricFileError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/lamp.ies"), std::string::npos);
  }
}

// An EULUMDAT file: one field a line. Lines 1-42 are the header (line 3
// the symmetry, 24 the conversion factor, 29 the lamps' flux), the C
// angles start on line 43, then the gamma angles and the intensities (with
// four C angles and two gamma angles: from line 49, a plane per two lines).
std::string ldtFile(int symmetry, const std::vector<double>& c, const std::vector<double>& gamma,
                    const std::vector<double>& intensities, const std::string& flux = "2000",
                    const std::string& factor = "1") {
  std::string t = "spectrace test\n1\n" + std::to_string(symmetry) + "\n" + std::to_string(c.size()) + "\n0\n" +
                  std::to_string(gamma.size()) + "\n0\nreport\ntest luminaire\nT-1\ntest.ldt\n2026\n";
  for (int k = 0; k < 9; ++k) t += "100\n";  // dimensions, mm
  t += "100\n80\n" + factor + "\n0\n1\n1\nLED\n" + flux + "\n3000\n90\n20\n";
  for (int k = 0; k < 10; ++k) t += "0.5\n";  // direct ratios
  for (double a : c) t += fmt::format("{}\n", a);
  for (double a : gamma) t += fmt::format("{}\n", a);
  for (double v : intensities) t += fmt::format("{:.17g}\n", v);
  return t;
}

TEST(EulumdatFile, ReadsDecimalCommas) {
  // As a comma locale writes the file: the factor 1,5 and the intensities.
  std::string text = ldtFile(1, {0, 90, 180, 270}, {0, 45, 90}, {300.5, 200.25, 0}, "2000", "1,5");
  for (const char* from : {"300.5\n", "200.25\n"}) {
    std::string to = from;
    to[to.find('.')] = ',';
    text.replace(text.find(from), std::string(from).size(), to);
  }
  const PhotometricTable t = parseEulumdat(text, "comma.ldt");
  EXPECT_DOUBLE_EQ(t.at(0, 0), 300.5 * 1.5 * 2.0);  // cd/klm x factor x 2000 lm / 1000
  EXPECT_DOUBLE_EQ(t.at(0, 1), 200.25 * 1.5 * 2.0);
  // Two commas are not a number.
  EXPECT_THROW(parseEulumdat(ldtFile(1, {0, 90, 180, 270}, {0, 45, 90}, {300, 200, 0}, "2000", "1,5,1"), "x.ldt"),
               PhotometricFileError);
}

TEST(EulumdatFile, RotationalSymmetryAndUnits) {
  const PhotometricTable t = parseEulumdat(ldtFile(1, {0, 90, 180, 270}, {0, 45, 90}, {300, 200, 0}), "lamp.ldt");
  EXPECT_EQ(t.cDegrees, (std::vector<double>{0, 360}));
  ASSERT_TRUE(t.ratedLumens);
  EXPECT_EQ(*t.ratedLumens, 2000.0);
  EXPECT_EQ(t.inputWatts, 20.0);
  EXPECT_DOUBLE_EQ(t.intensity(77.0, 0.0), 600.0);  // 300 cd/klm of 2000 lm
  EXPECT_DOUBLE_EQ(t.intensity(200.0, 45.0), 400.0);
  const PhotometricTable scaled =
      parseEulumdat(ldtFile(1, {0, 90, 180, 270}, {0, 45, 90}, {300, 200, 0}, "2000", "1.5"), "lamp.ldt");
  EXPECT_DOUBLE_EQ(scaled.intensity(0.0, 0.0), 900.0);
}

TEST(EulumdatFile, EverySymmetryUnfolds) {
  const std::vector<double> c = {0, 90, 180, 270}, g = {0, 90};
  // 4: C0-C180 and C90-C270 planes; the file holds C0 and C90.
  const PhotometricTable quadrant = parseEulumdat(ldtFile(4, c, g, {10, 1, 20, 2}), "q.ldt");
  EXPECT_EQ(quadrant.cDegrees, (std::vector<double>{0, 90, 180, 270, 360}));
  EXPECT_DOUBLE_EQ(quadrant.intensity(180.0, 0.0), 20.0);
  EXPECT_DOUBLE_EQ(quadrant.intensity(270.0, 0.0), 40.0);
  EXPECT_DOUBLE_EQ(quadrant.intensity(300.0, 0.0), quadrant.intensity(60.0, 0.0));
  // 2: the C0-C180 plane; the file holds C0, C90, C180.
  const PhotometricTable c0 = parseEulumdat(ldtFile(2, c, g, {10, 1, 20, 2, 30, 3}), "c0.ldt");
  EXPECT_DOUBLE_EQ(c0.intensity(270.0, 0.0), 40.0);
  EXPECT_DOUBLE_EQ(c0.intensity(180.0, 0.0), 60.0);
  EXPECT_DOUBLE_EQ(c0.intensity(315.0, 90.0), c0.intensity(45.0, 90.0));
  // 3: the C90-C270 plane; the file holds C270, then C0 and C90.
  const PhotometricTable c90 = parseEulumdat(ldtFile(3, c, g, {10, 1, 20, 2, 30, 3}), "c90.ldt");
  EXPECT_DOUBLE_EQ(c90.intensity(270.0, 0.0), 20.0);
  EXPECT_DOUBLE_EQ(c90.intensity(0.0, 0.0), 40.0);
  EXPECT_DOUBLE_EQ(c90.intensity(180.0, 0.0), 40.0);  // the image of C0
  EXPECT_DOUBLE_EQ(c90.intensity(135.0, 0.0), c90.intensity(45.0, 0.0));
  // 0: every plane.
  const PhotometricTable full = parseEulumdat(ldtFile(0, c, g, {10, 1, 20, 2, 30, 3, 40, 4}), "full.ldt");
  EXPECT_EQ(full.cDegrees, (std::vector<double>{0, 90, 180, 270, 360}));
  EXPECT_DOUBLE_EQ(full.intensity(270.0, 0.0), 80.0);
  EXPECT_DOUBLE_EQ(full.intensity(315.0, 0.0), 50.0);  // between C270 and C360 = C0
}

// The same luminaire as IES and as EULUMDAT gives the same table.
TEST(EulumdatFile, MatchesTheSameLuminaireInIes) {
  std::vector<double> gamma, perKlm;
  for (int g = 0; g <= 90; g += 10) {
    gamma.push_back(g);
    perKlm.push_back(1000.0 * std::cos(g * kPi / 180.0) / 2.0);  // 2000 lm of lamps: twice this in candela
  }
  const PhotometricTable ldt = parseEulumdat(ldtFile(1, {0}, gamma, perKlm), "lambert.ldt");
  const PhotometricTable ies = parseIes(iesFile("2000", "1", kTenVertical, "0", {lambertianRow()}, 10, 1), "l.ies");
  for (double c : {0.0, 33.0, 250.0})
    for (double g : {0.0, 15.0, 42.0, 89.0}) EXPECT_NEAR(ldt.intensity(c, g) * 0.9, ies.intensity(c, g), 1e-9);
  EXPECT_NEAR(ldt.tableLumens() * 0.9, ies.tableLumens(), 1e-9);
}

void expectLdtRefused(const std::string& text, const std::string& fragment) {
  try {
    parseEulumdat(text, "bad.ldt");
    ADD_FAILURE() << "accepted a file that should fail with '" << fragment << "'";
  } catch (const PhotometricFileError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(EulumdatFile, RefusalsNameTheFileAndLine) {
  const std::vector<double> c = {0, 90, 180, 270}, g = {0, 90};
  expectLdtRefused(ldtFile(4, c, g, {10, 1, 20}), "bad.ldt:51: the file ends");
  expectLdtRefused(ldtFile(4, c, g, {10, 1, 20, 2, 7}), "bad.ldt:53: 1 more lines after the 2 x 2 intensities");
  expectLdtRefused(ldtFile(4, c, g, {10, 1, -20, 2}), "bad.ldt:51: intensity -20 at C 90, gamma 0 is negative");
  expectLdtRefused(ldtFile(4, {0, 90, 80, 270}, g, {10, 1, 20, 2}), "bad.ldt:45: C angle 3 of 4 is 80");
  expectLdtRefused(ldtFile(4, c, {0, 90, 90}, {10, 1, 1, 20, 2, 2}), "bad.ldt:49: gamma angle 3 of 3 is 90");
  expectLdtRefused(ldtFile(5, c, g, {10, 1, 20, 2}), "bad.ldt:3: the symmetry indicator Isym is 5");
  expectLdtRefused(ldtFile(4, {0, 45, 180, 270}, g, {10, 1, 20, 2}), "bad.ldt:3: symmetry 4 needs a C plane at 90");
  expectLdtRefused(ldtFile(4, c, g, {10, 1, 20, 2}, "0"), "bad.ldt:29: the lamps' total luminous flux is 0");
  expectLdtRefused(ldtFile(4, c, g, {10, 1, 20, 2}, "2000", "x"), "bad.ldt:24: 'x' is not a number");
}

TEST(PhotometricFile, ChoosesTheReaderByExtension) {
  try {
    readPhotometricFile("/tmp/lamp.txt");
    ADD_FAILURE() << "accepted a .txt file";
  } catch (const PhotometricFileError& e) {
    EXPECT_NE(std::string(e.what()).find("/tmp/lamp.txt: a photometric file is IES LM-63 (.ies) or EULUMDAT (.ldt)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(readPhotometricFile("/nonexistent/lamp.LDT"), PhotometricFileError);
}

}  // namespace
}  // namespace spectrace
