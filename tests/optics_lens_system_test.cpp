// Exact references for the lens system camera (camera/lens_system_camera.cpp),
// each scene rendered on the CPU reference and on lavapipe, which must give
// the same film bit for bit:
//   1. Through the N-BK7 singlet, collimated lasers at the F, d and C lines
//      land where a real ray trace in double (Sellmeier index, Snell and
//      Fresnel, written here apart from the kernel) puts their centroids,
//      within a tenth of a pixel, in the order normal dispersion gives.
//   2. The double Gauss's paraxial focal length, measured through the
//      renderer (a thin laser near the axis, its landing point at two
//      sensor distances: f = -h / slope), agrees with the system matrix's
//      within 0.5%.
//   3. A diffuse plate through each lens: camera connections against analog
//      transport, per pixel within 5 sigma (and by chi-square).
//   4. The lens scenes of scenes/ render the same on both devices.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "camera/lens_system_camera.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "scene/scene_builders.h"
#include "spectrum/glass.h"
#include "support/device_renders.h"
#include "support/object_scenes.h"
#include "support/render_comparison.h"
#include "support/test_scale.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;
using testing::directionToWorld;
using testing::toWorld;

CompileOptions lightPaths(bool connect) {
  CompileOptions o;
  o.lightPaths = true;
  o.cameraPaths = false;
  o.connect = connect;
  return o;
}

LensSurface surface(double radius, double thickness, double semiAperture, const std::string& glass = "",
                    bool stop = false) {
  LensSurface s;
  s.radiusM = radius;
  s.thicknessM = thickness;
  s.semiApertureM = semiAperture;
  s.stop = stop;
  if (!glass.empty()) {
    const SellmeierGlass* g = glassNamed(glass);
    s.medium.label = g->name;
    s.medium.b = g->b;
    s.medium.cUm2 = g->cUm2;
  }
  return s;
}

// Thorlabs LB1676 (data/lenses/nbk7_biconvex_100mm.json) behind a stop,
// with the sensor `back` behind its last surface.
LensPrescription singlet(double back) {
  LensPrescription p;
  p.surfaces = {surface(0.0, 0.0, 0.0127, "", true), surface(0.1024, 0.00358, 0.0127, "N-BK7"),
                surface(-0.1024, back, 0.0127)};
  return p;
}

std::shared_ptr<const CameraModel> lensModel(const LensPrescription& p) {
  LensSystem lens;
  lens.prescription = p;
  lens.source.file = "<test lens>";
  lens.surfacesPtr = "/surfaces";
  return lensSystemModel(lens);
}

// The double Gauss as the scene loader reads it from data/lenses.
LensPrescription doubleGauss(double back) {
  // Appended piece by piece: GCC 12 warns (wrongly, -Warray-bounds) on
  // std::string + a long literal.
  std::string text = R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "lens": {"file": ")";
  text.append(SPECTRACE_SOURCE_DIR);
  text.append(R"(/data/lenses/double_gauss_50mm.json"}},
      "lights": [{"type": "point", "position": [0, 0, 1], "power_w": 1, "spd": {"line_nm": 550}}]})");
  const Scene scene = parseScene(text, "lens_scene.json");
  LensPrescription p = lensSystemOf(scene.camera)->prescription;
  p.surfaces.back().thicknessM = back;
  return p;
}

// --- a real ray trace in double, apart from the kernel ----------------------------
//
// Spheres by their centres (the kernel works from the vertex), the near
// intersection of a ray travelling towards -z, vector Snell and
// unpolarised Fresnel. Returns false where the ray misses an aperture.
struct TracedRay {
  glm::dvec2 onSensor;
  double transmission;
};
bool traceInDouble(const LensPrescription& lens, glm::dvec3 p, glm::dvec3 d, double lambdaNm, TracedRay& out) {
  const std::vector<double> z = lens.vertexZ();
  double before = 1.0, kept = 1.0;
  for (size_t i = 0; i < lens.surfaces.size(); ++i) {
    const LensSurface& s = lens.surfaces[i];
    glm::dvec3 normal(0.0, 0.0, 1.0);
    if (s.radiusM == 0.0) {
      p += d * ((z[i] - p.z) / d.z);
    } else {
      const glm::dvec3 centre(0.0, 0.0, z[i] - s.radiusM);
      const glm::dvec3 oc = p - centre;
      const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - s.radiusM * s.radiusM;
      const double root = std::sqrt(b * b - c);
      // A convex face (R > 0) is met first, a concave one (R < 0) second.
      p += d * (s.radiusM > 0.0 ? -b - root : -b + root);
      normal = (p - centre) / s.radiusM;  // towards +z at the vertex either way
    }
    if (p.x * p.x + p.y * p.y > s.semiApertureM * s.semiApertureM) return false;
    const double after = s.medium.indexAt(lambdaNm);
    if (after != before) {
      const double eta = before / after, cosI = -glm::dot(d, normal);
      const double cosT = std::sqrt(1.0 - eta * eta * (1.0 - cosI * cosI));
      const double rs = (eta * cosI - cosT) / (eta * cosI + cosT), rp = (cosI - eta * cosT) / (cosI + eta * cosT);
      kept *= 1.0 - 0.5 * (rs * rs + rp * rp);
      d = glm::normalize(eta * d + (eta * cosI - cosT) * normal);
    }
    before = after;
  }
  out.onSensor = glm::dvec2(p + d * (-p.z / d.z));
  out.transmission = kept;
  return true;
}

// The flux-weighted centroid on the sensor of a collimated laser of radius
// rho centred at height h, by rings of equal area and equal angle steps.
glm::dvec2 laserCentroidInDouble(const LensPrescription& lens, double h, double rho, double lambdaNm) {
  constexpr int kRings = 200, kSteps = 256;
  glm::dvec2 sum(0.0);
  double weight = 0.0;
  for (int i = 0; i < kRings; ++i)
    for (int j = 0; j < kSteps; ++j) {
      const double r = rho * std::sqrt((i + 0.5) / kRings), phi = 2.0 * M_PI * (j + 0.5) / kSteps;
      TracedRay ray;
      if (!traceInDouble(lens, {r * std::cos(phi), h + r * std::sin(phi), 1.0}, {0.0, 0.0, -1.0}, lambdaNm, ray))
        continue;
      sum += ray.transmission * ray.onSensor;
      weight += ray.transmission;
    }
  return sum / weight;
}

// The centroid of bin `bin`'s counts, in the camera frame: the image is
// flipped upright, so column c's centre lies at x = W/2 - (c + 1/2) pw
// and row r's at y = -H/2 + (r + 1/2) ph (shaders/sensor.h).
glm::dvec2 filmCentroid(const SpectralHistogram& h, const Camera& camera, uint32_t bin, double* total = nullptr) {
  const double pw = camera.sensorWidthM / camera.pixelsX, ph = camera.sensorHeightM / camera.pixelsY;
  glm::dvec2 sum(0.0);
  double weight = 0.0;
  for (int row = 0; row < camera.pixelsY; ++row)
    for (int col = 0; col < camera.pixelsX; ++col) {
      const double c = realOf(h.count(uint32_t(row * camera.pixelsX + col), bin));
      const glm::dvec2 centre(0.5 * camera.sensorWidthM - (col + 0.5) * pw,
                              -0.5 * camera.sensorHeightM + (row + 0.5) * ph);
      sum += c * centre;
      weight += c;
    }
  if (total) *total = weight / double(h.unitsPerBeam);
  return sum / weight;
}

Light laser(const Camera& camera, glm::dvec3 centre, double radius, double lambdaNm) {
  Light l = surfaceLight(LightType::Laser, toWorld(camera, centre), directionToWorld(camera, {0.0, 0.0, -1.0}), 1.0,
                         makeLineSpd(lambdaNm));
  l.radiusM = radius;
  return l;
}

// --- 1. the singlet's colour fringe ---------------------------------------------------
//
// The sensor 95 mm behind the lens, about 3.5 mm before the d line's focus
// (f = 99.7 mm), so each laser (radius 0.5 mm, 3 mm off the axis) makes a
// disk some 35 um across, 1 um pixels, the three centroids some 15 um
// apart: blue focuses nearest the lens and has come nearest the axis.
TEST(OpticsLensSystem, SingletPutsEachLineWhereARealRayTraceDoes) {
  const LensPrescription lens = singlet(0.095);
  Scene scene = bareSensorScene(0.0003, 0.0003, 300, 300, 3);
  scene.spectrum = {440.0, 680.0, 3};  // one line in each 80 nm bin
  scene.camera.model = lensModel(lens);
  const double lines[3] = {kLineFNm, kLineDNm, kLineCNm};
  const double h = 0.003, rho = 0.0005;
  for (int i = 0; i < 3; ++i) scene.lights.push_back(laser(scene.camera, {0.0, h, 0.2}, rho, lines[i]));
  for (size_t i = 0; i < scene.lights.size(); ++i) scene.lights[i].label = "/lights/" + std::to_string(i);
  const uint64_t beams = testing::scaledBeams(3'000'000, 600'000);
  const RenderResult r = testing::renderOnBothDevices(scene, beams, 7, lightPaths(true));
  const double pixel = scene.camera.sensorWidthM / scene.camera.pixelsX;
  double y[3];
  for (int i = 0; i < 3; ++i) {
    const glm::dvec2 expected = laserCentroidInDouble(lens, h, rho, lines[i]);
    double counted = 0.0;
    const glm::dvec2 measured = filmCentroid(r.histogram, scene.camera, uint32_t(i), &counted);
    y[i] = measured.y;
    std::printf("  %.2f nm: centroid (%.4f, %.4f) um, real ray trace (%.4f, %.4f) um, %.0f beams\n", lines[i],
                measured.x * 1e6, measured.y * 1e6, expected.x * 1e6, expected.y * 1e6, counted);
    // The spot's own scatter puts its centroid within 0.02 pixels (5 sigma:
    // a 35 um disk's RMS radius over the root of 1e5 or more beams).
    EXPECT_GT(counted, 1e5);
    EXPECT_NEAR(measured.x, expected.x, 0.1 * pixel) << lines[i] << " nm";
    EXPECT_NEAR(measured.y, expected.y, 0.1 * pixel) << lines[i] << " nm";
  }
  // Longitudinal chromatic aberration of a positive singlet: the shorter
  // the wavelength, the nearer its focus, the nearer the axis its spot.
  EXPECT_LT(y[0], y[1]);
  EXPECT_LT(y[1], y[2]);
  EXPECT_GT(y[1] - y[0], 10.0 * pixel);
}

// --- 2. the double Gauss's focal length -------------------------------------------------
//
// A laser of radius 50 um at h = 1 mm (a twelfth of the aperture: the
// spherical aberration's share is of order 1e-4) at 587.56 nm, with the
// sensor 30 mm and then 40 mm behind the last surface. The ray leaves the
// last surface with slope u = (y2 - y1) / 10 mm, and f = -h / u.
TEST(OpticsLensSystem, DoubleGaussFocalLengthMatchesTheSystemMatrix) {
  const double h = 0.001, backs[2] = {0.030, 0.040};
  double y[2];
  for (int k = 0; k < 2; ++k) {
    const LensPrescription lens = doubleGauss(backs[k]);
    Scene scene = bareSensorScene(0.0004, 0.002, 40, 400, 1);
    scene.spectrum = {580.0, 600.0, 1};
    scene.camera.model = lensModel(lens);
    scene.lights = {laser(scene.camera, {0.0, h, 0.2}, 5e-5, kLineDNm)};
    const uint64_t beams = testing::scaledBeams(400'000, 100'000);
    const RenderResult r = testing::renderOnBothDevices(scene, beams, 11 + k, lightPaths(true));
    y[k] = filmCentroid(r.histogram, scene.camera, 0).y;
  }
  const double measured = -h / ((y[1] - y[0]) / (backs[1] - backs[0]));
  const double expected = paraxialCardinal(doubleGauss(0.03), kLineDNm)->focalLengthM;
  std::printf("  focal length through the renderer %.5f mm, system matrix %.5f mm\n", measured * 1e3, expected * 1e3);
  EXPECT_NEAR(measured, expected, 0.005 * expected);
  EXPECT_NEAR(expected, 0.05036, 0.00001);  // Kolb et al.'s 50 mm lens: f = 50.36 mm
}

// --- 3. a plate through each lens: connections against analog ------------------------
//
// A diffuse plate of reflectance 0.8, 160 mm wide, 80 mm before the lens's
// front opening, lit by a spot on the axis 20 mm before it that shines
// only on it (a 60 degree cone facing away from the lens, so the sensor
// gets its light only through the plate); 8 x 8 pixels.
Scene plateScene(const LensPrescription& lens, double sensor) {
  Scene scene = bareSensorScene(sensor, sensor, 8, 8, 4);
  scene.camera.model = lensModel(lens);
  const double plateZ = lens.frontZ() + 0.08;
  Light spot = surfaceLight(LightType::Spot, toWorld(scene.camera, {0.0, 0.0, plateZ - 0.02}),
                            directionToWorld(scene.camera, {0.0, 0.0, 1.0}), 2.0, makeLineSpd(550.0));
  spot.coneHalfAngleDeg = 60.0;
  scene.lights = {spot};
  scene.objects = {testing::namedObject(
      "plate", 0, testing::rectShape(scene.camera, {0.0, 0.0, plateZ}, {0.0, 0.0, -1.0}, {1.0, 0.0, 0.0}, {0.16, 0.16}),
      testing::diffuseMaterial(0.8))};
  return scene;
}

void expectConnectionsMatchAnalog(const Scene& scene, uint64_t analogBeams, uint64_t connectBeams) {
  const uint64_t small = testing::scaledBeams(200'000, 100'000);
  testing::renderOnBothDevices(scene, small, 21, lightPaths(false));
  testing::renderOnBothDevices(scene, small, 22, lightPaths(true));
  const RenderResult analog = testing::renderOn(DeviceChoice::Cpu, scene, analogBeams, 31, lightPaths(false));
  const RenderResult connected = testing::renderOn(DeviceChoice::Cpu, scene, connectBeams, 32, lightPaths(true));
  const auto result = testing::compareRenders(
      testing::pixelEstimates(analog.histogram, analog.plan, analogBeams),
      testing::pixelEstimates(connected.histogram, connected.plan, connectBeams), "analog vs connected");
  EXPECT_EQ(result.cells, 64);
  EXPECT_GT(result.pValue, 0.001);  // a correct renderer fails one run in a thousand
}

TEST(OpticsLensSystem, PlateThroughTheSingletConnectionsMatchAnalog) {
  expectConnectionsMatchAnalog(plateScene(singlet(0.11), 0.04), testing::scaledBeams(20'000'000, 4'000'000),
                               testing::scaledBeams(1'000'000, 200'000));
}

TEST(OpticsLensSystem, PlateThroughTheDoubleGaussConnectionsMatchAnalog) {
  expectConnectionsMatchAnalog(plateScene(doubleGauss(0.0415), 0.024), testing::scaledBeams(20'000'000, 4'000'000),
                               testing::scaledBeams(1'000'000, 200'000));
}

// --- 4. the scenes ----------------------------------------------------------------------
//
// Every lens scene in scenes/, with its defaults (four wavelengths a beam,
// camera connections), equal bit for bit on both devices.
TEST(OpticsLensSystem, LensScenesAreTheSameOnBothDevices) {
  for (const char* name : {"singlet_fringe", "double_gauss"}) {
    const Scene scene = loadScene(fs::path(SPECTRACE_SOURCE_DIR) / "scenes" / (std::string(name) + ".json"));
    ASSERT_TRUE(lensSystemOf(scene.camera)) << name;
    const RenderResult r = testing::renderOnBothDevices(scene, testing::scaledBeams(200'000, 50'000), 41, {});
    EXPECT_GT(r.summary.countedBeams, 0u) << name;
  }
}

}  // namespace
}  // namespace spectrace
