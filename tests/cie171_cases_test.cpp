// The analytical light-source cases of CIE 171:2006, "Test cases to assess
// the accuracy of lighting computer programs" (CIE, Vienna, 2006): direct
// illuminance on a plane from a point source of known intensity, from a
// Lambertian rectangular area source parallel to the plane and from one
// perpendicular to it, and from a circular area source parallel to it,
// each against its closed form. The report's own rooms and tabulated
// values are not reproduced here; these are its configurations at the
// scale of a 0.6 m bare sensor of 24 x 24 pixels (the plane), with the
// closed forms integrated over each pixel (host/reference/exact_solution.cpp):
// - point: E = I cos^3(gamma) / h^2;
// - parallel rectangle and disk: the configuration factor of a parallel
//   rectangle or coaxial disk times the exitance;
// - perpendicular rectangle: Lambert's polygon form factor, which for a
//   rectangle standing on the plane's normal gives the perpendicular
//   configuration factor of the report's wall-mounted sources.
// Each is rendered on lavapipe and the CPU reference with the same beams,
// bit for bit, and the CPU's film is checked within 5 sigma per pixel, by a
// chi-square over the pixels and in total (testing::expectMatchesExactImage).
#include <gtest/gtest.h>

#include <string>

#include "scene/scene.h"
#include "support/device_renders.h"
#include "support/render_comparison.h"
#include "support/test_scale.h"

namespace spectrace {
namespace {

Scene planeUnder(const std::string& lightsAndObjects) {
  return parseScene(R"({"spectrum": {"min_nm": 380, "max_nm": 780, "bins": 8},
      "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0],
                 "sensor": {"width_m": 0.6, "height_m": 0.6, "pixels": [24, 24]}},
      "render": {"wavelengths_per_beam": 1}, )" +
                        lightsAndObjects + "}",
                    "cie171.json");
}

const uint64_t kBeams = testing::scaledBeams(2'000'000, 200'000);

TEST(Cie171, PointSourceOfKnownIntensity) {
  // 100 cd in every direction: 400 pi lm of the V(lambda) peak's line.
  const Scene scene = planeUnder(R"("lights": [{"type": "point", "position": [0.05, -0.03, 0.3],
      "power_lm": 1256.6370614359172, "spd": {"line_nm": 555}}])");
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, kBeams, 11), kBeams, "point source");
}

TEST(Cie171, RectangularSourceParallelToThePlane) {
  const Scene scene = planeUnder(R"("objects": [{"type": "rect", "center": [0, 0.02, 0.3], "normal": [0, 0, -1],
      "u_axis": [1, 0, 0], "size_m": [0.3, 0.15], "material": {"type": "absorber"},
      "emission": {"power_lm": 1000, "spd": "D65"}}])");
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, kBeams, 12), kBeams,
                                   "rectangular source, parallel");
}

TEST(Cie171, RectangularSourcePerpendicularToThePlane) {
  // A 0.2 x 0.2 m source beside the plane's edge, from 0.05 to 0.25 m
  // above it, facing across it.
  const Scene scene = planeUnder(R"("objects": [{"type": "rect", "center": [-0.35, 0, 0.15], "normal": [1, 0, 0],
      "u_axis": [0, 1, 0], "size_m": [0.2, 0.2], "material": {"type": "absorber"},
      "emission": {"power_lm": 1000, "spd": "D65"}}])");
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, kBeams, 13), kBeams,
                                   "rectangular source, perpendicular");
}

TEST(Cie171, CircularSourceParallelToThePlane) {
  const Scene scene = planeUnder(R"("objects": [{"type": "disk", "center": [0, 0, 0.25], "normal": [0, 0, -1],
      "radius_m": 0.12, "material": {"type": "absorber"}, "emission": {"power_lm": 1000, "spd": "A"}}])");
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, kBeams, 14), kBeams,
                                   "circular source, parallel");
}

}  // namespace
}  // namespace spectrace
