// The lens system's host side: model glasses, the paraxial optics against
// closed forms, the lens files (JSON and pbrt-v4's tables), and the
// refusals, each naming the file and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "camera/lens_system_camera.h"
#include "json/scene_error.h"
#include "scene/scene.h"
#include "spectrum/glass.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;

TEST(ModelGlass, HasItsIndexAndAbbeNumber) {
  for (const auto& [nd, vd] : {std::pair{1.5168, 64.17}, std::pair{1.699, 30.1}, std::pair{1.8, 25.0}}) {
    const auto g = modelGlass(nd, vd);
    ASSERT_TRUE(g);
    const double d = sellmeierIndex(g->b, g->cUm2, kLineDNm), f = sellmeierIndex(g->b, g->cUm2, kLineFNm),
                 c = sellmeierIndex(g->b, g->cUm2, kLineCNm);
    EXPECT_NEAR(d, nd, 1e-12);
    EXPECT_NEAR((d - 1.0) / (f - c), vd, 1e-9 * vd);
    EXPECT_GT(sellmeierIndex(g->b, g->cUm2, 400.0), sellmeierIndex(g->b, g->cUm2, 700.0));  // normal dispersion
  }
  EXPECT_FALSE(modelGlass(0.9, 50.0));
  EXPECT_FALSE(modelGlass(1.5, 0.0));
}

LensSurface surface(double radius, double thickness, double n) {
  LensSurface s;
  s.radiusM = radius;
  s.thicknessM = thickness;
  s.semiApertureM = 0.01;
  if (n != 1.0) s.medium.b = {n * n - 1.0, 0.0, 0.0};
  return s;
}

// A thick lens in air: 1/f = (n - 1) (1/R1 - 1/R2 + (n - 1) t / (n R1 R2)),
// its back focal distance f (1 - (n - 1) t / (n R1)).
TEST(LensPrescription, ThickLensMatchesTheLensmakersFormula) {
  const double n = 1.6, r1 = 0.05, r2 = -0.08, t = 0.006;
  LensPrescription lens;
  lens.surfaces = {surface(r1, t, n), surface(r2, 0.07, 1.0)};
  const auto cardinal = paraxialCardinal(lens, 550.0);
  ASSERT_TRUE(cardinal);
  const double f = 1.0 / ((n - 1.0) * (1.0 / r1 - 1.0 / r2 + (n - 1.0) * t / (n * r1 * r2)));
  EXPECT_NEAR(cardinal->focalLengthM, f, 1e-12);
  const ParaxialMatrix m = paraxialMatrix(lens, 550.0);
  EXPECT_NEAR(-m.a / m.c, f * (1.0 - (n - 1.0) * t / (n * r1)), 1e-12);
  EXPECT_NEAR(m.a * m.d - m.b * m.c, 1.0, 1e-12);  // in air on both sides
}

// After focusing at D, the matrix from the object D before the sensor to
// the sensor images: its b element (height on the sensor from the
// object's angle) is zero.
TEST(LensPrescription, FocusPutsTheObjectDistanceInFocus) {
  LensPrescription lens;
  lens.surfaces = {surface(0.05, 0.006, 1.6), surface(-0.08, 0.0, 1.0)};
  for (double distance : {0.5, 2.0, 100.0}) {
    const auto back = focusedBackThicknessM(lens, distance, 587.5618);
    ASSERT_TRUE(back);
    const double body = 0.006;
    const double before = distance - body - *back;  // object to the first vertex
    const ParaxialMatrix m = paraxialMatrix(lens, 587.5618);
    // [1 back; 0 1] m [1 before; 0 1]: b = (a + back c) before + b + back d.
    const double b = (m.a + *back * m.c) * before + m.b + *back * m.d;
    EXPECT_NEAR(b, 0.0, 1e-12 * distance) << distance;
  }
  // Four focal lengths (about 0.24 m here) is the nearest a real image can be.
  EXPECT_FALSE(focusedBackThicknessM(lens, 0.2, 587.5618));
}

class LensFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("spectrace_lens_files_" + std::to_string(::getpid()));
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir / name) << text; }
  // A scene whose camera has `lens` (a JSON object's text).
  Scene scene(const std::string& lens) {
    const std::string text = R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "lens": )" + lens +
                             R"(}, "lights": [{"type": "point", "position": [0, 0, 1], "power_w": 1,
                                 "spd": {"line_nm": 550}}]})";
    return parseScene(text, dir / "scene.json");
  }
  // The message of the SceneError parsing it throws.
  std::string refusal(const std::string& lens) {
    try {
      scene(lens);
    } catch (const SceneError& e) {
      return e.what();
    }
    return "(accepted)";
  }
  fs::path dir;
};

const char* kSinglet = R"([
  {"radius_m": 0, "thickness_m": 0, "semi_aperture_m": 0.0127, "stop": true},
  {"radius_m": 0.1024, "thickness_m": 0.00358, "semi_aperture_m": 0.0127, "medium": "N-BK7"},
  {"radius_m": -0.1024, "thickness_m": 0.0985, "semi_aperture_m": 0.0127}])";

TEST_F(LensFiles, InlineFileAndPbrtTableGiveTheSameLens) {
  write("singlet.json", std::string(R"({"name": "LB1676", "surfaces": )") + kSinglet + "}");
  // pbrt-v4's table of the same lens, N-BK7 by its index at the d line.
  write("singlet.dat", "# radius thickness index aperture\n0 0 0 25.4\n102.4 3.58 1.5168 25.4\n-102.4 98.5 0 25.4\n");
  const Scene inlineLens = scene(std::string(R"({"surfaces": )") + kSinglet + "}");
  const Scene fromFile = scene(R"({"file": "singlet.json"})");
  const Scene fromTable = scene(R"({"file": "singlet.dat"})");
  const LensPrescription& a = lensSystemOf(inlineLens.camera)->prescription;
  const LensPrescription& b = lensSystemOf(fromFile.camera)->prescription;
  const LensPrescription& c = lensSystemOf(fromTable.camera)->prescription;
  ASSERT_EQ(a.surfaces.size(), 3u);
  ASSERT_EQ(c.surfaces.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(a.surfaces[i].radiusM, b.surfaces[i].radiusM);
    EXPECT_NEAR(a.surfaces[i].radiusM, c.surfaces[i].radiusM, 1e-15);
    EXPECT_NEAR(a.surfaces[i].thicknessM, c.surfaces[i].thicknessM, 1e-15);
    EXPECT_NEAR(a.surfaces[i].semiApertureM, c.surfaces[i].semiApertureM, 1e-15);
  }
  EXPECT_TRUE(c.surfaces[0].stop);
  EXPECT_NEAR(c.surfaces[1].medium.indexAt(400.0), 1.5168, 1e-12);  // one index for every wavelength
  EXPECT_FALSE(c.disperses());
  EXPECT_TRUE(a.disperses());
  EXPECT_NEAR(a.surfaces[1].medium.indexAt(kLineDNm), 1.5168, 5e-5);
  // The lens file is among the files a state records.
  EXPECT_EQ(referencedFiles(fromFile).size(), 1u);
  EXPECT_TRUE(referencedFiles(inlineLens).empty());
}

// The shipped double Gauss two ways: pbrt-v4's table (one index a glass)
// and the JSON file (model glasses of the same nd): the same lens at the
// d line, focused alike.
TEST_F(LensFiles, ShippedDoubleGaussTableAndJsonAgreeAtTheDLine) {
  const std::string lenses = std::string(SPECTRACE_SOURCE_DIR) + "/data/lenses/";
  const Scene table = scene(R"({"focus_distance_m": 1, "file": ")" + lenses + R"(dgauss.50mm.dat"})");
  const Scene json = scene(R"({"focus_distance_m": 1, "file": ")" + lenses + R"(double_gauss_50mm.json"})");
  const LensPrescription& a = lensSystemOf(table.camera)->prescription;
  const LensPrescription& b = lensSystemOf(json.camera)->prescription;
  ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
  EXPECT_FALSE(a.disperses());
  EXPECT_TRUE(b.disperses());
  for (size_t i = 0; i < a.surfaces.size(); ++i) {
    EXPECT_NEAR(a.surfaces[i].radiusM, b.surfaces[i].radiusM, 1e-15) << i;
    EXPECT_NEAR(a.surfaces[i].semiApertureM, b.surfaces[i].semiApertureM, 1e-15) << i;
    EXPECT_NEAR(a.surfaces[i].medium.indexAt(kLineDNm), b.surfaces[i].medium.indexAt(kLineDNm), 1e-12) << i;
    EXPECT_EQ(a.surfaces[i].stop, b.surfaces[i].stop) << i;
  }
  EXPECT_NEAR(a.surfaces.back().thicknessM, b.surfaces.back().thicknessM, 1e-12);
  EXPECT_NEAR(paraxialCardinal(a, kLineDNm)->focalLengthM, 0.0503582, 1e-7);  // Kolb et al.: 50.36 mm
}

// The f-number f / (2 x entrance pupil radius): with the stop at the
// singlet's front, the pupil is the stop itself; the double Gauss opens to
// f/2.03 (nominally f/2), and f_number narrows its stop to the pupil it
// names.
TEST_F(LensFiles, FNumberNarrowsTheStop) {
  const Scene singlet = scene(std::string(R"({"f_number": 8, "surfaces": )") + kSinglet + "}");
  const LensPrescription& a = lensSystemOf(singlet.camera)->prescription;
  const double f = paraxialCardinal(a, kLineDNm)->focalLengthM;
  EXPECT_NEAR(a.surfaces[0].semiApertureM, f / 16.0, 1e-15);
  EXPECT_NEAR(*fNumber(a, kLineDNm), 8.0, 1e-12);
  const std::string lenses = std::string(SPECTRACE_SOURCE_DIR) + "/data/lenses/";
  const Scene wide = scene(R"({"focus_distance_m": 1, "file": ")" + lenses + R"(double_gauss_50mm.json"})");
  EXPECT_NEAR(*fNumber(lensSystemOf(wide.camera)->prescription, kLineDNm), 2.030, 0.001);
  const Scene narrow =
      scene(R"({"focus_distance_m": 1, "f_number": 5.6, "file": ")" + lenses + R"(double_gauss_50mm.json"})");
  const LensPrescription& b = lensSystemOf(narrow.camera)->prescription;
  EXPECT_NEAR(*fNumber(b, kLineDNm), 5.6, 1e-12);
  EXPECT_NEAR(b.surfaces[5].semiApertureM, 0.00855 * 2.0301534 / 5.6, 1e-7);
  const std::string tooWide = refusal(R"({"f_number": 1.4, "file": ")" + lenses + R"(double_gauss_50mm.json"})");
  EXPECT_NE(tooWide.find("/camera/lens/f_number: f/1.4 is wider than the lens opens"), std::string::npos) << tooWide;
}

TEST_F(LensFiles, FocusDistanceSolvesTheLastThickness) {
  const Scene s = scene(std::string(R"({"focus_distance_m": 1.5, "surfaces": )") + kSinglet + "}");
  const LensPrescription& lens = lensSystemOf(s.camera)->prescription;
  EXPECT_EQ(*focusedBackThicknessM(lens, 1.5, kLineDNm), lens.surfaces.back().thicknessM);
  EXPECT_GT(lens.surfaces.back().thicknessM, 0.0985);  // nearer than infinity: the sensor moves back
}

TEST_F(LensFiles, RefusalsNameTheFileAndTheField) {
  const auto expectRefusal = [&](const std::string& lens, const std::string& where, const std::string& what) {
    const std::string message = refusal(lens);
    EXPECT_NE(message.find(where), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  };
  // No stop; two stops.
  expectRefusal(R"({"surfaces": [{"radius_m": 0.1, "thickness_m": 0.1, "semi_aperture_m": 0.01}]})",
                "scene.json: /camera/lens/surfaces", "no surface is the aperture stop");
  expectRefusal(R"({"surfaces": [{"radius_m": 0, "thickness_m": 0.01, "semi_aperture_m": 0.01, "stop": true},
                                 {"radius_m": 0, "thickness_m": 0.1, "semi_aperture_m": 0.01, "stop": true}]})",
                "/camera/lens/surfaces/1/stop", "a second aperture stop");
  // A semi-aperture beyond the sphere.
  expectRefusal(R"({"surfaces": [{"radius_m": 0, "thickness_m": 0, "semi_aperture_m": 0.01, "stop": true},
                                 {"radius_m": 0.005, "thickness_m": 0.1, "semi_aperture_m": 0.01}]})",
                "/camera/lens/surfaces/1/semi_aperture_m", "larger than the surface's sphere allows");
  // Surfaces that cross: a steep convex face (its rim 2.7 mm behind its
  // vertex) 0.5 mm before a flat one.
  expectRefusal(R"({"surfaces": [{"radius_m": 0, "thickness_m": 0.001, "semi_aperture_m": 0.01, "stop": true},
                                 {"radius_m": 0.02, "thickness_m": 0.0005, "semi_aperture_m": 0.01, "medium": "N-BK7"},
                                 {"radius_m": 0, "thickness_m": 0.1, "semi_aperture_m": 0.01}]})",
                "/camera/lens/surfaces/1/thickness_m", "surfaces 1 and 2 cross");
  // A focus that cannot be solved.
  expectRefusal(std::string(R"({"focus_distance_m": 0.3, "surfaces": )") + kSinglet + "}",
                "/camera/lens/focus_distance_m", "cannot be focused");
  // An index below 1, inline and in a pbrt table.
  expectRefusal(R"({"surfaces": [{"radius_m": 0, "thickness_m": 0.1, "semi_aperture_m": 0.01, "stop": true,
                                  "medium": {"nd": 0.8, "vd": 40}}]})",
                "/camera/lens/surfaces/0/medium/nd", "an index below 1");
  write("bad.dat", "0 0 0 25\n50 3 0.9 25\n-50 90 0 25\n");
  expectRefusal(R"({"file": "bad.dat"})", "bad.dat: line 2", "an index below 1");
  write("steep.dat", "# a surface steeper than its aperture\n0 0 0 25\n5 3 1.5 25\n-50 90 0 25\n");
  expectRefusal(R"({"file": "steep.dat"})", "steep.dat: line 3 (aperture diameter)",
                "larger than the surface's sphere");
  // A table with no stop, or no surface: the table's own terms, not a JSON
  // pointer.
  write("nostop.dat", "35.98 1.22 1.54 23.7\n11.70 9.99 0 18.0\n");
  expectRefusal(R"({"file": "nostop.dat"})", "nostop.dat: its surface lines: no surface is the aperture stop",
                "give exactly one line a curvature radius of 0");
  write("empty.dat", "# no surfaces\n");
  expectRefusal(R"({"file": "empty.dat"})", "empty.dat: its surface lines", "a lens needs at least one surface");
  // In a JSON lens file, its own path and field.
  write("bad.json", R"({"surfaces": [{"radius_m": 0, "thickness_m": 0.1, "semi_aperture_m": 0.01, "stop": true,
                                      "medium": "N-BK8"}]})");
  expectRefusal(R"({"file": "bad.json"})", "bad.json: /surfaces/0/medium", "unknown medium \"N-BK8\"");
  expectRefusal(R"({"file": "missing.json"})", "/camera/lens/file", "missing.json");
  // The sensor in glass.
  expectRefusal(R"({"surfaces": [{"radius_m": 0, "thickness_m": 0.1, "semi_aperture_m": 0.01, "stop": true,
                                  "medium": "N-BK7"}]})",
                "/camera/lens/surfaces/0/medium", "must be air");
}

}  // namespace
}  // namespace spectrace
