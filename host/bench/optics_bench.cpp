#include "bench/optics_bench.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "camera/pinhole_camera.h"
#include "lights/photometric_file.h"
#include "render/renderer.h"
#include "scene/scene_builders.h"

namespace spectrace {
namespace {

// Two renders of one variant, seeds 1 and 2, after a small one that keeps
// pipeline compilation out of the timing.
struct RenderPair {
  RenderResult a, b;
  double traceSeconds() const { return std::min(a.traceWallSeconds, b.traceWallSeconds); }
};

RenderPair renderPair(const Scene& scene, const Device& device, uint64_t beams, const OpticsBenchOptions& bench,
                      const std::function<void(RenderOptions&)>& configure) {
  RenderOptions options;
  options.beams = beams;
  options.loop.cancel = bench.cancel;
  options.loop.checkpointSeconds = 0;
  if (configure) configure(options);
  RenderOptions warm = options;
  warm.beams = std::min<uint64_t>(beams, 1 << 14);
  render(scene, warm, device);
  RenderPair pair;
  options.seed = 1;
  pair.a = render(scene, options, device);
  options.seed = 2;
  pair.b = render(scene, options, device);
  return pair;
}

std::vector<double> meanImage(const RenderPair& pair) {
  std::vector<double> mean(pair.a.image.irradiance.size());
  for (size_t i = 0; i < mean.size(); ++i)
    mean[i] = 0.5 * (double(pair.a.image.irradiance[i]) + double(pair.b.image.irradiance[i]));
  return mean;
}

// relMSE from the seeds' difference against the reference (see the header).
double relativeMse(const RenderPair& pair, const std::vector<double>& reference) {
  double squaredError = 0.0, squaredSignal = 0.0;
  for (size_t i = 0; i < reference.size(); ++i) {
    const double d = double(pair.a.image.irradiance[i]) - double(pair.b.image.irradiance[i]);
    squaredError += 0.5 * d * d;
    squaredSignal += reference[i] * reference[i];
  }
  return squaredError / squaredSignal;
}

// The matched scenes' error (the header): relMSE of Y over the pixels
// whose centres lie in the central `interior` fraction of the sensor's
// width and height.
double relativeMseOfY(const RenderPair& pair, double interior) {
  const RenderImage& a = pair.a.image;
  const RenderImage& b = pair.b.image;
  double squaredError = 0.0, squaredSignal = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const double u = (x + 0.5) / a.width - 0.5, v = (y + 0.5) / a.height - 0.5;
      if (std::abs(u) > 0.5 * interior || std::abs(v) > 0.5 * interior) continue;
      const size_t p = size_t(y) * a.width + x;
      const double ya = a.xyz[p * 3 + 1], yb = b.xyz[p * 3 + 1];
      squaredError += 0.5 * (ya - yb) * (ya - yb);
      squaredSignal += 0.25 * (ya + yb) * (ya + yb);
    }
  return squaredError / squaredSignal;
}

OpticsRow rowOf(const std::string& scene, const std::string& variant, const RenderPair& pair,
                const std::vector<double>& reference) {
  OpticsRow row;
  row.scene = scene;
  row.variant = variant;
  row.device = pair.a.deviceKind;
  row.deviceName = pair.a.deviceName;
  row.primitives = pair.a.plan.device.primitives.size();
  row.beams = pair.a.beamsTraced;
  row.counted = pair.a.summary.countedBeams;
  row.traceSeconds = pair.traceSeconds();
  row.relMse = relativeMse(pair, reference);
  row.fom = row.relMse > 0.0 ? 1.0 / (row.relMse * row.traceSeconds) : 0.0;
  return row;
}

}  // namespace

Shape tessellatedSphere(const glm::dvec3& centre, double radius, uint64_t triangles) {
  // Rings x segments quads, the polar ones as single triangles: about
  // 2 x rings x segments triangles, with segments = 2 x rings.
  const uint32_t rings = std::max<uint32_t>(3, uint32_t(std::lround(std::sqrt(double(triangles) / 4.0))));
  const uint32_t segments = 2 * rings;
  Shape shape;
  shape.type = ShapeType::Mesh;
  shape.closed = true;
  shape.vertices.push_back(centre + glm::dvec3(0.0, 0.0, radius));  // north pole
  for (uint32_t r = 1; r < rings; ++r) {
    const double theta = std::numbers::pi * double(r) / double(rings);
    for (uint32_t s = 0; s < segments; ++s) {
      const double phi = 2.0 * std::numbers::pi * double(s) / double(segments);
      shape.vertices.push_back(centre + radius * glm::dvec3(std::sin(theta) * std::cos(phi),
                                                            std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  }
  const uint32_t south = uint32_t(shape.vertices.size());
  shape.vertices.push_back(centre - glm::dvec3(0.0, 0.0, radius));
  auto ringVertex = [&](uint32_t r, uint32_t s) { return 1 + (r - 1) * segments + s % segments; };
  // Counter-clockwise seen from outside.
  for (uint32_t s = 0; s < segments; ++s) shape.triangles.push_back({0, ringVertex(1, s), ringVertex(1, s + 1)});
  for (uint32_t r = 1; r + 1 < rings; ++r)
    for (uint32_t s = 0; s < segments; ++s) {
      shape.triangles.push_back({ringVertex(r, s), ringVertex(r + 1, s), ringVertex(r + 1, s + 1)});
      shape.triangles.push_back({ringVertex(r, s), ringVertex(r + 1, s + 1), ringVertex(r, s + 1)});
    }
  for (uint32_t s = 0; s < segments; ++s)
    shape.triangles.push_back({ringVertex(rings - 1, s), south, ringVertex(rings - 1, s + 1)});
  return shape;
}

// A grey sphere lit by a spot that just covers it, through a pinhole: the
// mesh scene. (Most beams meet the sphere, so the image converges at a
// rate that shows the mesh's cost, not a light that mostly misses.)
Scene opticsMeshScene(uint64_t triangles) {
  Scene scene = bareSensorScene(0.024, 0.024, 128, 128, SpectrumRange{}.bins);
  scene.camera.model = pinholeModel({0.04, 0.001});
  // At the sphere's centre, 1.04 m away; asin(0.3 / 1.04) = 16.8 degrees: the whole sphere.
  Light light = surfaceLight(LightType::Spot, {0.6, 0.6, 0.4}, glm::normalize(glm::dvec3(-0.6, -0.6, 0.6)), 10.0,
                             makeLineSpd(550.0), "550 nm");
  light.coneHalfAngleDeg = 17.5;
  scene.lights.push_back(light);
  SceneObject sphere;
  sphere.label = "/objects/0";
  sphere.shape = tessellatedSphere({0.0, 0.0, 1.0}, 0.3, triangles);
  sphere.material.type = MaterialType::Diffuse;
  sphere.material.reflectanceNm = {550.0};
  sphere.material.reflectance = {0.5};
  scene.objects.push_back(sphere);
  scene.render.beams = 1'000'000;
  return scene;
}

Scene emittingSphereScene(uint64_t triangles) {
  Scene scene = bareSensorScene(0.6, 0.6, 24, 24, SpectrumRange{}.bins);
  SceneObject sphere;
  sphere.label = "/objects/0";
  if (triangles == 0) {
    sphere.shape.type = ShapeType::Sphere;
    sphere.shape.center = {0.0, 0.0, 0.2};
    sphere.shape.radiusM = 0.06;
    sphere.shape.closed = true;
  } else {
    sphere.shape = tessellatedSphere({0.0, 0.0, 0.2}, 0.06, triangles);
  }
  Light light;
  light.type = LightType::Object;
  light.label = "/objects/0/emission";
  light.powerW = 1.0;
  light.spd = makeLineSpd(550.0);
  light.spdLabel = "550 nm";
  placeEmission(sphere.shape, false, 0, light);
  scene.lights.push_back(light);
  scene.objects.push_back(sphere);
  return scene;
}

Scene photometricScene(double cStepDeg, double gammaStepDeg) {
  Scene scene = bareSensorScene(0.6, 0.6, 24, 24, SpectrumRange{}.bins);
  auto table = std::make_shared<PhotometricTable>();
  for (double c = 0.0; c <= 360.0 + 1e-9; c += cStepDeg) table->cDegrees.push_back(std::min(c, 360.0));
  for (double g = 0.0; g <= 180.0 + 1e-9; g += gammaStepDeg) table->gammaDegrees.push_back(std::min(g, 180.0));
  // Different in every quadrant, brighter below the horizon than above it.
  constexpr double kRad = std::numbers::pi / 180.0;
  for (double c : table->cDegrees)
    for (double g : table->gammaDegrees)
      table->candela.push_back(800.0 * (0.25 + std::max(std::cos(g * kRad), 0.0)) *
                               (1.0 + 0.7 * std::cos(c * kRad) + 0.4 * std::sin(c * kRad)));
  Light light = surfaceLight(LightType::Photometric, {0.0, 0.0, 0.25}, {0.0, 0.0, -1.0}, 1.0, makeLineSpd(550.0),
                             "550 nm");
  light.photometry = std::move(table);
  light.uAxis = {1.0, 0.0, 0.0};
  scene.lights.push_back(light);
  return scene;
}

// The ColorChecker scene through the N-BK7 singlet of data/lenses
// (f = 100 mm) focused on the chart, on a 24 x 16 mm sensor: its middle.
Scene singletColorChecker(const Scene& colorChecker, const std::filesystem::path& scenesDir) {
  const std::string text = R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1],
    "sensor": {"width_m": 0.024, "height_m": 0.016, "pixels": [240, 160]},
    "lens": {"file": "../data/lenses/nbk7_biconvex_100mm.json", "focus_distance_m": 0.56}},
    "lights": [{"type": "point", "position": [0, 0, 1], "power_w": 1, "spd": {"line_nm": 550}}]})";
  Scene scene = colorChecker;
  scene.camera = parseScene(text, scenesDir / "singlet_colorchecker.json").camera;
  return scene;
}

std::vector<OpticsRow> runOpticsBench(const std::vector<DeviceSpec>& devices, const OpticsBenchOptions& bench) {
  std::vector<OpticsRow> rows;
  auto add = [&](OpticsRow row) {
    if (bench.onRow) bench.onRow(row);
    rows.push_back(std::move(row));
  };
  // The objects section's scenes, empty when it does not run (an if, not
  // ?:, whose temporary GCC 12 takes for an uninitialised shared_ptr).
  auto objectScene = [&](auto make) {
    Scene scene;
    if (bench.objects) scene = make();
    return scene;
  };
  const Scene prism = objectScene([&] { return loadScene(bench.scenesDir / "prism.json"); });
  const Scene colorChecker = objectScene([&] { return loadScene(bench.scenesDir / "colorchecker.json"); });
  const Scene thinLens = objectScene([&] { return loadScene(bench.scenesDir / "thin_lens.json"); });
  const Scene doubleGauss = objectScene([&] { return loadScene(bench.scenesDir / "double_gauss.json"); });
  const Scene singlet = objectScene([&] { return singletColorChecker(colorChecker, bench.scenesDir); });
  // Two variants of one scene, measured against one reference (the first
  // variant's mean), so their FOM ratio is a ratio of squared error x time.
  struct Variant {
    const char* name;
    uint64_t beams;
    std::function<void(RenderOptions&)> configure;
  };
  auto compareVariants = [&](const Scene& scene, const char* sceneName, const Variant& first, const Variant& second,
                             const Device& device) {
    RenderPair a = renderPair(scene, device, first.beams, bench, first.configure);
    RenderPair b = renderPair(scene, device, second.beams, bench, second.configure);
    const std::vector<double> reference = meanImage(a);
    add(rowOf(sceneName, first.name, a, reference));
    add(rowOf(sceneName, second.name, b, reference));
    return std::pair{std::move(a), std::move(b)};
  };
  // The scenes matched pixel for pixel with pbrt-v4 (scenes/bench/fom_*):
  // the square covers the central 0.727 of the sensor; its interior, 0.8 of that.
  const std::pair<const char*, uint64_t> matched[] = {{"fom_emitter", 16'777'216}, {"fom_lit_grey", 16'777'216}};
  constexpr double kSquareInterior = 0.8 * (0.6 * 0.024 / 1.1) / 0.018;
  const Scene mesh = objectScene([&] { return opticsMeshScene(1'000'000); });
  const Scene smallMesh = objectScene([&] { return opticsMeshScene(1'000); });
  // Emission from a surface: the draw is O(1) in the triangles (an alias
  // table), so rows differ by the first walk through the emitter's tree.
  const std::pair<const char*, uint64_t> emitters[] = {
      {"analytic", 0}, {"1k triangles", 1'000}, {"1M triangles", 1'000'000}};
  std::vector<Scene> emitterScenes;
  for (const auto& [name, triangles] : emitters)
    if (bench.objects) emitterScenes.push_back(emittingSphereScene(triangles));
  // A luminaire's table: the patch is drawn in O(1) of its size (an alias
  // table); steps of 30 (C) by 15 (gamma) degrees against 0.5 by 0.25.
  const std::pair<const char*, double> tables[] = {{"13 x 13 angles", 30.0}, {"721 x 721 angles", 0.5}};
  std::vector<Scene> photometricScenes;
  for (const auto& [name, step] : tables)
    if (bench.objects) photometricScenes.push_back(photometricScene(step, step / 2.0));
  for (const DeviceSpec& spec : devices) {
    const auto device = Device::open(spec);
    const size_t firstRow = rows.size();
    // Each estimator (compile/estimators.h) on each, at the scene's beams.
    struct Estimator {
      const char* name;
      bool lightPaths, cameraPaths;
    };
    constexpr Estimator kEstimators[] = {{"light", true, false}, {"camera", false, true}, {"both", true, true}};
    for (const auto& [name, beams] : matched) {
      if (!bench.matched) break;
      const Scene scene = loadScene(bench.scenesDir / "bench" / (std::string(name) + ".json"));
      for (const Estimator& e : kEstimators) {
        const RenderPair pair = renderPair(scene, *device, beams, bench, [&](RenderOptions& o) {
          o.plan.lightPaths = e.lightPaths;
          o.plan.cameraPaths = e.cameraPaths;
        });
        OpticsRow row = rowOf(name, e.name, pair, meanImage(pair));
        row.relMse = relativeMseOfY(pair, kSquareInterior);
        row.fom = row.relMse > 0.0 ? 1.0 / (row.relMse * row.traceSeconds) : 0.0;
        add(std::move(row));
      }
    }
    if (bench.objects) {
      {
        const RenderPair pair = renderPair(prism, *device, 4'000'000, bench, {});
        add(rowOf("prism", "default", pair, meanImage(pair)));
      }
      // Connection against analog, analog at ten times the beams.
      // (Light paths only: camera paths would count every path both count.)
      compareVariants(colorChecker, "colorchecker", {"connect", 2'000'000, [](RenderOptions& o) { o.plan.cameraPaths = false; }},
                      {"analog", 20'000'000, [](RenderOptions& o) {
                         o.plan.connect = false;
                         o.plan.cameraPaths = false;
                       }},
                      *device);
      // The same through the thin lens (f/2, three depths).
      compareVariants(thinLens, "thin lens", {"connect", 2'000'000, [](RenderOptions& o) { o.plan.cameraPaths = false; }},
                      {"analog", 20'000'000, [](RenderOptions& o) {
                         o.plan.connect = false;
                         o.plan.cameraPaths = false;
                       }},
                      *device);
      // And through each lens system: the ColorChecker through the double
      // Gauss, and (part of it) through the N-BK7 singlet.
      compareVariants(doubleGauss, "double Gauss",
                      {"connect", 2'000'000, [](RenderOptions& o) { o.plan.cameraPaths = false; }},
                      {"analog", 20'000'000, [](RenderOptions& o) { o.plan.connect = false; }}, *device);
      compareVariants(singlet, "singlet", {"connect", 2'000'000, [](RenderOptions& o) { o.plan.cameraPaths = false; }},
                      {"analog", 20'000'000, [](RenderOptions& o) { o.plan.connect = false; }}, *device);
      {
        const RenderPair pair = renderPair(mesh, *device, 2'000'000, bench, {});
        add(rowOf("mesh 1M triangles", "default", pair, meanImage(pair)));
      }
      // The same beams either way: brute force finds the same closest
      // surfaces, so only the time differs. (A beam on a shared edge may meet
      // either triangle first; the row says whether the images differ.)
      const auto [bvh, brute] =
          compareVariants(smallMesh, "mesh 1k triangles", {"bvh", 500'000, {}},
                          {"brute force", 500'000, [](RenderOptions& o) { o.plan.bruteForceObjects = true; }}, *device);
      rows.back().sameImageAsFirst = bvh.a.image.irradiance == brute.a.image.irradiance;
      // Each whole, then cut after emission (the profile's first stage:
      // light, wavelength, origin and direction), which times the draw alone.
      const auto emissionRows = [&](const Scene& scene, const char* sceneName, const std::string& variant) {
        const RenderPair pair = renderPair(scene, *device, 2'000'000, bench, {});
        add(rowOf(sceneName, variant, pair, meanImage(pair)));
        const RenderPair cut = renderPair(scene, *device, 2'000'000, bench, [](RenderOptions& o) {
          o.tracer.profileStage = device::kProfileStageEmission;
        });
        OpticsRow row = rowOf(sceneName, variant + ", emission", cut, meanImage(pair));
        row.relMse = row.fom = 0.0;  // nothing is counted
        add(std::move(row));
      };
      for (size_t i = 0; i < emitterScenes.size(); ++i)
        emissionRows(emitterScenes[i], "emitting sphere", emitters[i].first);
      for (size_t i = 0; i < photometricScenes.size(); ++i)
        emissionRows(photometricScenes[i], "photometric light", tables[i].first);
    }
    for (size_t i = firstRow; i < rows.size(); ++i) rows[i].reference = spec.capabilities.reference;
  }
  return rows;
}

}  // namespace spectrace
