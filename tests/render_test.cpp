// Whole renders through the library: device choice, interruption and
// checkpoints (no finished work is lost), and results that do not depend on
// batch size, workgroup size, thread count or how the beams are split.
#include <gtest/gtest.h>

#include <atomic>
#include <limits>

#include "camera/pinhole_camera.h"
#include "support/cpu_trace.h"
#include "support/device_renders.h"
#include "render/renderer.h"
#include "support/test_scale.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

Scene smallScene() {
  Scene scene = testing::bareSensorScene(0.02, 0.02, 40, 30, 24);
  Light disk = testing::surfaceLight(LightType::Disk, {0.002, 0.0, 0.01}, {0, 0, -1}, 2.0, *cieIlluminant("D65"));
  disk.radiusM = 0.004;
  scene.lights = {disk, testing::pointLight({-0.005, 0.003, 0.004}, 0.5, makeBlackbodySpd(3000, 360, 830))};
  return scene;
}

RenderResult renderWith(const Device& device, uint64_t beams, uint64_t batch, uint32_t workgroup = 64,
                        unsigned threads = 0, uint64_t first = 0) {
  RenderOptions options;
  options.beams = beams;
  options.firstBeam = first;
  options.seed = 99;
  options.loop.batchBeams = batch;
  options.tracer.workgroupSize = workgroup;
  options.tracer.cpuThreads = threads;
  return render(smallScene(), options, device);
}

TEST(Render, AutoPicksAHardwareGpuElseTheCpuReference) {
  RenderOptions options;
  options.beams = 1000;
  std::string logged;
  options.loop.log = [&](const std::string& line) { logged += line + "\n"; };
  const RenderResult result = render(smallScene(), options);
  bool hardware = false;
  for (const DeviceSpec& spec : listDevices()) hardware = hardware || spec.capabilities.hardwareGpu;
  // lavapipe (a CPU implementation of Vulkan) is not taken by auto
  EXPECT_EQ(result.deviceKind, hardware ? DeviceKind::Vulkan : DeviceKind::Cpu);
  EXPECT_NE(logged.find(result.deviceName), std::string::npos) << "auto must say which device it picked";
}

TEST(Render, CancelledRenderKeepsExactlyTheFinishedBeams) {
  const uint64_t beams = testing::scaledBeams(4'000'000, 400'000) / 4 * 4;  // four whole batches
  for (DeviceChoice device : {DeviceChoice::Gpu, DeviceChoice::Cpu}) {
    std::atomic<bool> cancel{false};
    RenderOptions options;
    options.beams = beams;
    options.seed = 99;
    options.device = device;
    options.loop.batchBeams = beams / 4;
    options.loop.cancel = &cancel;
    options.loop.onProgress = [&](uint64_t done, uint64_t) { cancel.store(done >= beams / 2); };
    const RenderResult partial = render(smallScene(), options);
    EXPECT_EQ(partial.beamsTraced, beams / 2);
    // The partial histogram is exactly that of the first two batches, and the image
    // is normalised by the beams actually traced.
    SpectralHistogram reference;
    traceOnCpu(partial.plan, 0, partial.beamsTraced, reference);
    EXPECT_EQ(partial.histogram.counts(), reference.counts());
    const double perCount = partial.plan.irradiancePerCount(partial.beamsTraced);
    uint64_t pixelCount = 0;
    for (uint32_t b = 0; b < partial.histogram.bins; ++b) pixelCount += partial.histogram.at(0, b);
    EXPECT_NEAR(partial.image.irradiance[0], double(pixelCount) * perCount, 1e-6 * double(pixelCount) * perCount + 1e-30);
  }
}

TEST(Render, CheckpointsCarryTheFinishedBeams) {
  RenderOptions options;
  options.beams = 3'000'000;
  options.device = DeviceChoice::Gpu;
  options.loop.batchBeams = 1'000'000;
  options.loop.checkpointSeconds = 1e-9;  // after every batch but the last
  std::vector<uint64_t> checkpoints;
  options.loop.onCheckpoint = [&](const RenderImage& image, uint64_t done, const std::string& device) {
    EXPECT_EQ(image.irradiance.size(), 40u * 30u);
    EXPECT_FALSE(device.empty());
    checkpoints.push_back(done);
  };
  render(smallScene(), options);
  EXPECT_EQ(checkpoints, (std::vector<uint64_t>{1'000'000, 2'000'000}));
}

// Counts and exact-colour sums, both integers, must agree bit for bit.
void expectSameHistogram(const SpectralHistogram& a, const SpectralHistogram& b, const char* what) {
  EXPECT_EQ(a.counts(), b.counts()) << what;
  EXPECT_EQ(a.colourSums(), b.colourSums()) << what;
  EXPECT_EQ(a.squaredWeightSums(), b.squaredWeightSums()) << what;
  EXPECT_EQ(a.countedBeams, b.countedBeams) << what;
}

// Images resolved on one device from identical histograms are identical.
void expectSameImage(const RenderImage& a, const RenderImage& b, const char* what) {
  EXPECT_EQ(a.rgb, b.rgb) << what;
  EXPECT_EQ(a.xyz, b.xyz) << what;
  EXPECT_EQ(a.irradiance, b.irradiance) << what;
}

TEST(Render, BitIdenticalWhateverTheBatchWorkgroupAndThreads) {
  // 3 million beams at full scale; the batch sizes keep their proportions
  // to the total at any test scale (700,001, 999,999, 1,234,567 at full).
  const uint64_t n = testing::scaledBeams(3'000'000, 300'000);
  const auto part = [n](uint64_t atFullScale) { return atFullScale * n / 3'000'000; };
  // The shared devices: each render clears the film it takes from the
  // device's buffers.
  const Device& gpu = testing::sharedDevice(DeviceChoice::Gpu);
  const Device& cpu = testing::sharedDevice(DeviceChoice::Cpu);
  ASSERT_EQ(gpu.capabilities().kind, DeviceKind::Vulkan);
  const RenderResult gpuReference = renderWith(gpu, n, n);
  const auto& reference = gpuReference.histogram;
  ASSERT_TRUE(reference.hasExactColour());
  const auto expectSameRender = [&](const RenderResult& result, const char* what) {
    expectSameImage(result.image, gpuReference.image, what);
    expectSameHistogram(result.histogram, reference, what);
  };
  expectSameRender(renderWith(gpu, n, part(700'001)), "odd batches");
  expectSameRender(renderWith(gpu, n, 0, 256), "workgroup 256");
  expectSameRender(renderWith(gpu, n, 0, 32), "workgroup 32");
  const RenderResult cpuOneThread = renderWith(cpu, n, 0, 64, 1);
  expectSameHistogram(cpuOneThread.histogram, reference, "cpu, 1 thread");
  expectSameImage(cpuOneThread.image, renderWith(cpu, n, part(999'999), 64, 2).image, "cpu image, 1 vs 2 threads");
  expectSameHistogram(renderWith(cpu, n, part(1'234'567), 64, 2).histogram, reference, "cpu, 2 threads");
  // Two renders over disjoint beam ranges merge into the whole.
  auto first = renderWith(gpu, n / 3, 0);
  first.histogram.merge(renderWith(cpu, n - n / 3, 0, 64, 0, n / 3).histogram);
  expectSameHistogram(first.histogram, reference, "merged halves");
}

}  // namespace
}  // namespace spectrace

namespace spectrace {
namespace {

// A pipeline specialised to the scene (absent light types, light choice,
// pinhole, exact colour, aiming compiled out), or to any one of those,
// gives bit-identical results to the general pipeline.
TEST(Render, SpecialisedPipelineMatchesGeneralBitForBit) {
  std::vector<Scene> scenes;
  scenes.push_back(smallScene());  // disk + point, bare
  Scene laser = bareSensorScene(0.01, 0.01, 8, 8, 16);
  Light beam = surfaceLight(LightType::Laser, {0.001, 0.0, 0.05}, {0, 0, -1}, 1.0, makeLineSpd(532.0));
  beam.radiusM = 0.003;
  laser.lights = {beam};  // one light, one type
  scenes.push_back(laser);
  Scene pinhole = smallScene();
  pinhole.camera.model = pinholeModel({0.002, 0.001});
  for (auto& l : pinhole.lights) l.position.z += 0.01;
  scenes.push_back(pinhole);
  Scene aimedPanel = bareSensorScene(0.01, 0.01, 8, 8, 16);
  aimedPanel.camera.model = pinholeModel({0.005, 0.0005});
  Light panel = surfaceLight(LightType::Disk, {0.0, 0.0, 0.1}, {0, 0, -1}, 1.0, *cieIlluminant("D65"));
  panel.radiusM = 0.02;
  aimedPanel.lights = {panel};  // aimed, with fractional weights
  scenes.push_back(aimedPanel);
  ASSERT_TRUE(compileScene(aimedPanel, 1).film.weighted());
  // Each feature alone on the one scene where it compiles the most away
  // (compiling a pipeline per feature and scene was most of this test's
  // time), and only at full test scale: at the sanitizer and validation
  // stages' reduced scales the host code those pipelines run is the same
  // as the whole specialisation's.
  const bool everyFeatureAlone = testing::testScale() >= 1.0;
  const auto featureAloneScene = [](uint32_t feature) -> size_t {
    switch (feature) {
      case kSpecialiseLightChoice: return 1;  // one light: no choice
      case kSpecialiseAim: return 1;          // nothing aimed: aiming compiled out
      case kSpecialiseCameraType: return 2;   // the pinhole's branch
      case kSpecialiseExactColour: return 3;  // per-beam colour with fractional weights
      // None of these scenes has objects: the optics tests check the
      // primitive and material types' specialisation against the CPU.
      case kSpecialiseObjectTypes: return std::numeric_limits<size_t>::max();
      default: return 0;                      // light types, uniform tables: two lights, two SPDs
    }
  };
  // The shared device keeps its compiled pipelines by their code and
  // constants, so the general pipeline, the same for every scene here,
  // compiles once for each colour mode.
  const Device& device = testing::sharedDevice(DeviceChoice::Gpu);
  ASSERT_EQ(device.capabilities().kind, DeviceKind::Vulkan);
  for (bool exactColour : {true, false}) {
    for (size_t s = 0; s < scenes.size(); ++s) {
      const Scene& scene = scenes[s];
      RenderOptions options;
      options.beams = 250'000;
      options.plan.exactColour = exactColour;
      const RenderResult specialised = render(scene, options, device);
      options.tracer.specialisedFeatures = kSpecialiseNone;
      const RenderResult general = render(scene, options, device);
      EXPECT_GT(general.histogram.countedBeams, 1000u);
      expectSameHistogram(specialised.histogram, general.histogram, "specialised vs general");
      expectSameImage(specialised.image, general.image, "specialised vs general");
      // Each specialisation alone (the benchmark measures them one by one).
      // With exact colour on only: each is a pipeline of its own to
      // compile, and exact colour off is one of them (and compiled out in
      // the whole specialisation above).
      for (uint32_t feature = 1; everyFeatureAlone && exactColour && feature < kSpecialiseAll; feature <<= 1) {
        if (featureAloneScene(feature) != s) continue;
        TracerOptions alone;
        alone.specialisedFeatures = feature;
        const std::unique_ptr<Tracer> tracer = device.makeTracer(general.plan, alone);
        tracer->trace(0, options.beams);
        expectSameHistogram(tracer->download(), general.histogram,
                            ("feature " + std::to_string(feature) + " alone vs general").c_str());
      }
    }
  }
}

}  // namespace
}  // namespace spectrace

namespace spectrace {
namespace {

// Storing only the bins the lights can reach changes nothing but memory and
// time: histograms (expanded to the full spectrum) and images are
// bit-identical to storing every bin.
TEST(Render, TrimmedSpectrumMatchesFullSpectrumBitForBit) {
  struct Case {
    const char* name;
    Spd spd;
    uint32_t maxStoredBins;
  };
  const std::vector<Case> cases = {{"532 nm line", makeLineSpd(532.0), 1},
                                   {"F11 (380-780 nm)", *cieIlluminant("F11"), 82},
                                   {"Gaussian 589 nm", makeLineSpd(589.0, 2.0), 3}};
  const Device& gpu = testing::sharedDevice(DeviceChoice::Gpu);
  const Device& cpu = testing::sharedDevice(DeviceChoice::Cpu);
  ASSERT_EQ(gpu.capabilities().kind, DeviceKind::Vulkan);
  for (const auto& c : cases) {
    Scene scene = bareSensorScene(0.02, 0.02, 8, 8, 94);
    Light disk = surfaceLight(LightType::Disk, {0.0, 0.0, 0.01}, {0, 0, -1}, 1.0, c.spd);
    disk.radiusM = 0.005;
    scene.lights = {disk};
    const CompiledScene trimmed = compileScene(scene, 1);
    EXPECT_LE(trimmed.film.storedBins, c.maxStoredBins) << c.name;
    for (const Device* device : {&gpu, &cpu}) {
      RenderOptions options;
      options.beams = 1'000'000;
      const RenderResult a = render(scene, options, *device);
      options.plan.trimSpectrum = false;
      const RenderResult b = render(scene, options, *device);
      EXPECT_EQ(b.plan.film.storedBins, 94u);
      EXPECT_GT(a.histogram.total(), 100'000u);
      expectSameHistogram(a.histogram, b.histogram, c.name);
      expectSameImage(a.image, b.image, c.name);
    }
  }
}

// Storing only the pixels beams can reach (the image of the lights through
// a pinhole, a laser's footprint) changes nothing but memory and time:
// histograms and images are bit-identical to storing the whole sensor.
TEST(Render, TrimmedSensorMatchesFullSensorBitForBit) {
  struct Case {
    const char* name;
    Scene scene;
    bool smaller;  // the window should be smaller than the sensor
  };
  std::vector<Case> cases;
  {
    Scene s = bareSensorScene(0.036, 0.024, 36, 24, 16);
    s.camera.model = pinholeModel({0.05, 0.0005});
    Light panel = surfaceLight(LightType::Rect, {0.05, 0.03, 0.5}, glm::normalize(glm::dvec3(0.1, 0.0, -1.0)), 1.0,
                               *cieIlluminant("D65"));
    panel.sizeM = {0.06, 0.04};
    panel.uAxis = {1, 0, 0};
    s.lights = {panel, pointLight({-0.04, 0.01, 0.3}, 0.2, *cieIlluminant("A"))};
    cases.push_back({"pinhole: tilted panel and point light off axis", s, true});
  }
  {
    Scene s = bareSensorScene(0.02, 0.02, 20, 20, 16);
    Light beam = surfaceLight(LightType::Laser, {0.003, -0.002, 0.05}, glm::normalize(glm::dvec3(0.02, 0.01, -1.0)),
                              1.0, makeLineSpd(532.0));
    beam.radiusM = 0.001;
    s.lights = {beam};
    cases.push_back({"bare: slanted laser", s, true});
  }
  {
    Scene s = bareSensorScene(0.02, 0.02, 16, 16, 16);
    s.camera.model = pinholeModel({0.01, 0.002});
    Light disk = surfaceLight(LightType::Disk, {0.0, 0.0, 0.0105}, glm::normalize(glm::dvec3(0.0, 1.0, -0.2)), 1.0,
                              *cieIlluminant("D65"));
    disk.radiusM = 0.003;  // reaches below the aperture plane: no bound, the whole sensor
    s.lights = {disk};
    cases.push_back({"pinhole: disk straddling the aperture plane", s, false});
  }
  const Device& gpu = testing::sharedDevice(DeviceChoice::Gpu);
  ASSERT_EQ(gpu.capabilities().kind, DeviceKind::Vulkan);
  for (const auto& c : cases) {
    const CompiledScene plan = compileScene(c.scene, 1);
    std::printf("%s: %llu of %llu pixels stored\n", c.name, (unsigned long long)plan.film.storedPixelCount(),
                (unsigned long long)plan.film.pixelCount());
    EXPECT_EQ(plan.film.storedPixelCount() < plan.film.pixelCount(), c.smaller) << c.name;
    RenderOptions options;
    options.beams = 1'000'000;
    // Light paths: camera paths go to the stored pixels only, so trimming
    // moves them (the same expectation, other bits; the closed forms of
    // OpticsReference.EmitterSquareMatchesItsClosedForm hold it).
    options.plan.cameraPaths = false;
    const RenderResult a = render(c.scene, options, gpu);
    options.plan.trimPixels = false;
    const RenderResult b = render(c.scene, options, gpu);
    EXPECT_EQ(b.plan.film.storedPixelCount(), b.plan.film.pixelCount());
    EXPECT_GT(a.histogram.countedBeams, 10'000u) << c.name;
    expectSameHistogram(a.histogram, b.histogram, c.name);
    expectSameImage(a.image, b.image, c.name);
  }
}

}  // namespace
}  // namespace spectrace
