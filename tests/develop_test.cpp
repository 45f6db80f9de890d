// develop without a download of the film: the CPU reference resolves its
// own device-layout counters (resolveStoredCountersOnCpu) and the resolve
// shader returns each pixel's exact sums, from which the host writes
// error.E and the film's summary. Both must equal what the downloaded
// histogram gives, bit for bit: a stored window and trimmed bins (laser),
// weighted counts with a squared-weight counter (aimed rect through a
// pinhole), per-beam colour counters (two spectra), and one spectral table.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <string>

#include "backend/cpu_tracer.h"
#include "backend/vulkan_tracer.h"
#include "compile/compile_scene.h"
#include "film/develop.h"
#include "film/pixel_variance.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

Scene sceneNamed(const std::string& name) { return loadScene(std::string(SPECTRACE_SOURCE_DIR) + "/scenes/" + name); }

// The largest pixel-bin, in full-weight beams.
double largestBinBeams(const SpectralHistogram& h) {
  unsigned __int128 largest = 0;
  for (size_t i = 0; i < h.counts().size() / h.counterWords(); ++i)
    largest = std::max(largest, wideValue(h.counter(device::kFilmChannelBins, i)));
  return realOf(device::WideCount{uint64_t(largest), uint64_t(largest >> 64)}) / double(h.unitsPerBeam);
}

// A pixel's bin counters, summed exactly.
device::WideCount pixelTotal(const SpectralHistogram& h, uint32_t pixel) {
  unsigned __int128 sum = 0;
  for (uint32_t b = 0; b < h.bins; ++b) sum += wideValue(h.count(pixel, b));
  return device::WideCount{uint64_t(sum), uint64_t(sum >> 64)};
}

void expectSameImage(const RenderImage& a, const RenderImage& b, const std::string& what) {
  EXPECT_EQ(a.rgb, b.rgb) << what;
  EXPECT_EQ(a.xyz, b.xyz) << what;
  EXPECT_EQ(a.irradiance, b.irradiance) << what;
  EXPECT_EQ(a.irradianceError, b.irradianceError) << what;
}

class DevelopWithoutDownload : public ::testing::TestWithParam<const char*> {};

TEST_P(DevelopWithoutDownload, EqualsDevelopingTheDownloadedHistogram) {
  const Scene scene = sceneNamed(GetParam());
  const CompiledScene plan = compileScene(scene, 7);
  constexpr uint64_t kBeams = 300'000;
  CpuTracer cpu(plan, 2);
  cpu.trace(0, kBeams);
  const SpectralHistogram film = cpu.download();
  ASSERT_GT(film.total(), 0u) << "the scene must count some beams";
  const ResolveParameters parameters = resolveParametersFor(scene, plan, kBeams);
  ASSERT_EQ(parameters.beams, kBeams);

  FilmSummary fromHistogram, fromCounters;
  const RenderImage reference = resolveOnCpu(film, parameters, &fromHistogram);
  const RenderImage cpuImage = cpu.develop(parameters, &fromCounters);
  expectSameImage(cpuImage, reference, "CPU counters vs histogram");
  ASSERT_EQ(reference.irradianceError.size(), reference.irradiance.size());
  EXPECT_EQ(fromCounters.countedBeams, film.countedBeams);
  EXPECT_EQ(fromCounters.largestBeams, largestBinBeams(film));
  EXPECT_EQ(fromHistogram.largestBeams, largestBinBeams(film));
  EXPECT_EQ(fromCounters.squaredWeights, fromHistogram.squaredWeights);

  // The error channel is the estimate of pixel_variance.h, pixel by pixel.
  const std::vector<double> relativeVariance = estimatedRelativeVariance(film, kBeams);
  for (size_t p = 0; p < relativeVariance.size(); ++p) {
    const double total = realOf(pixelTotal(film, uint32_t(p)));
    const float expected = std::isfinite(relativeVariance[p])
                               ? float(std::sqrt(relativeVariance[p]) * (total * parameters.irradiancePerCount))
                               : 0.0f;
    ASSERT_EQ(reference.irradianceError[p], expected) << "pixel " << p;
  }

  VulkanTracer gpu(testing::sharedVulkan(), plan);
  gpu.trace(0, kBeams);
  FilmSummary fromGpu;
  const RenderImage gpuImage = gpu.develop(parameters, &fromGpu);
  // RGB, XYZ and irradiance are float on the GPU (resolve_numerics_test);
  // the error and the summary come from exact integer sums, so they match.
  EXPECT_EQ(gpuImage.irradianceError, reference.irradianceError) << "GPU error.E";
  EXPECT_EQ(fromGpu.countedBeams, film.countedBeams);
  EXPECT_EQ(fromGpu.largestBeams, largestBinBeams(film));
  EXPECT_EQ(fromGpu.squaredWeights, fromHistogram.squaredWeights);
}

INSTANTIATE_TEST_SUITE_P(Scenes, DevelopWithoutDownload,
                         ::testing::Values("reference/laser_532.json", "reference/pinhole_rect.json",
                                           "showcase.json", "bench/throughput.json"),
                         [](const auto& info) {
                           std::string name = info.param;
                           name = name.substr(name.find('/') == std::string::npos ? 0 : name.find('/') + 1);
                           name = name.substr(0, name.find('.'));
                           return name;
                         });

// A render that does not download its film writes the same image and
// summary as one that does.
TEST(DevelopWithoutDownload, RenderWithoutTheFilmGivesTheSameImage) {
  const Scene scene = sceneNamed("reference/pinhole_rect.json");
  for (DeviceChoice device : {DeviceChoice::Cpu, DeviceChoice::Gpu}) {
    RenderOptions options;
    options.beams = 200'000;
    options.device = device;
    options.loop.checkpointSeconds = 0;
    const RenderResult withFilm = render(scene, options);
    options.outputs.downloadFilm = false;
    const RenderResult withoutFilm = render(scene, options);
    EXPECT_TRUE(withoutFilm.histogram.counts().empty());
    ASSERT_FALSE(withFilm.histogram.counts().empty());
    expectSameImage(withoutFilm.image, withFilm.image, "render without the film");
    EXPECT_EQ(withoutFilm.summary.countedBeams, withFilm.histogram.countedBeams);
    EXPECT_EQ(withoutFilm.summary.largestBeams, largestBinBeams(withFilm.histogram));
  }
}

}  // namespace
}  // namespace spectrace
