// The spectral EXR (one channel per bin, the layout of Fichet, Pacanowski and
// Wilkie, JCGT 2021) and the per-pixel error channel error.E: names and
// attributes as read by OpenEXR itself, the spectrum summing to the
// irradiance, a laser line in its one bin, the same channels whether the
// spectrum is trimmed or not, and error.E against the spread of renders with
// independent seeds.
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfChromaticities.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "backend/device.h"
#include "io/image.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "scene/scene_builders.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;

Scene laserScene() { return loadScene(std::string(SPECTRACE_SOURCE_DIR) + "/scenes/reference/laser_532.json"); }

RenderResult renderSpectral(const Scene& scene, bool trimSpectrum, DeviceChoice device = DeviceChoice::Cpu) {
  RenderOptions options;
  options.beams = 200'000;
  options.seed = 7;
  options.device = device;
  options.outputs.spectral = true;
  options.plan.trimSpectrum = trimSpectrum;
  return render(scene, options);
}

fs::path writeTemp(const RenderImage& image, const std::string& name) {
  const fs::path path = fs::temp_directory_path() / ("spectrace_spectral_film_" + name + ".exr");
  writeExr(path, image, {});
  return path;
}

std::vector<std::string> channelNames(const fs::path& path) {
  Imf::InputFile in(path.c_str());
  std::vector<std::string> names;
  for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) names.push_back(it.name());
  return names;
}

TEST(SpectralFilm, ChannelNameFollowsTheLayout) {
  EXPECT_EQ(spectralChannelName(552.5), "S0.552,500000nm");
  EXPECT_EQ(spectralChannelName(362.5), "S0.362,500000nm");
  EXPECT_EQ(spectralChannelName(1000.0 / 3.0), "S0.333,333333nm");
}

TEST(SpectralFilm, ChannelClashNamesTheFirstTwoBinsThatShareAName) {
  EXPECT_FALSE(spectralChannelClash({550.0, 550.000001, 550.000002}).has_value());
  const auto clash = spectralChannelClash({550.00000025, 550.00000075, 550.00000125, 550.00000175});
  ASSERT_TRUE(clash.has_value());
  EXPECT_EQ(clash->first, 1u);
  EXPECT_EQ(clash->second, 2u);
  EXPECT_EQ(clash->name, "S0.550,000001nm");
}

TEST(SpectralFilm, ChannelsAndAttributesReadBackThroughOpenExr) {
  const Scene scene = laserScene();
  const RenderResult result = renderSpectral(scene, true);
  const fs::path path = writeTemp(result.image, "layout");
  Imf::InputFile in(path.c_str());
  const Imf::Header& header = in.header();
  for (const char* name : {"R", "G", "B", "XYZ.X", "XYZ.Y", "XYZ.Z", "irradiance.E", "error.E"}) {
    const Imf::Channel* channel = header.channels().findChannel(name);
    ASSERT_NE(channel, nullptr) << name;
    EXPECT_EQ(channel->type, Imf::FLOAT) << name;
  }
  // 94 bins of 5 nm from 360 nm: centres 362.5, 367.5, ..., 827.5.
  int spectral = 0;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
    if (std::string(it.name()).rfind("S0.", 0) == 0) ++spectral;
  EXPECT_EQ(spectral, scene.spectrum.bins);
  for (int b = 0; b < scene.spectrum.bins; ++b) {
    const std::string name = spectralChannelName(360.0 + (b + 0.5) * 5.0);
    const Imf::Channel* channel = header.channels().findChannel(name);
    ASSERT_NE(channel, nullptr) << name;
    EXPECT_EQ(channel->type, Imf::FLOAT) << name;
  }
  EXPECT_NE(header.channels().findChannel("S0.362,500000nm"), nullptr);
  EXPECT_NE(header.channels().findChannel("S0.827,500000nm"), nullptr);
  const auto* version = header.findTypedAttribute<Imf::StringAttribute>("spectralLayoutVersion");
  ASSERT_NE(version, nullptr);
  EXPECT_EQ(version->value(), "1.0");
  const auto* units = header.findTypedAttribute<Imf::StringAttribute>("emissiveUnits");
  ASSERT_NE(units, nullptr);
  EXPECT_EQ(units->value(), "W.m^-2.nm^-1");

  // And our own reader gives back the bin centres and values bit for bit.
  const ExrContents back = readExr(path);
  EXPECT_EQ(back.image.spectralBinCentresNm, result.image.spectralBinCentresNm);
  EXPECT_EQ(back.image.spectralIrradiance, result.image.spectralIrradiance);
  EXPECT_EQ(back.image.irradianceError, result.image.irradianceError);
  fs::remove(path);
}

TEST(SpectralFilm, WithoutSpectralOnlyTheErrorChannelIsAdded) {
  RenderOptions options;
  options.beams = 100'000;
  options.device = DeviceChoice::Cpu;
  const RenderResult result = render(laserScene(), options);
  const fs::path path = writeTemp(result.image, "plain");
  const std::vector<std::string> names = channelNames(path);
  EXPECT_EQ(names.size(), 8u);  // R G B XYZ.X XYZ.Y XYZ.Z irradiance.E error.E
  EXPECT_NE(std::find(names.begin(), names.end(), "error.E"), names.end());
  Imf::InputFile in(path.c_str());
  EXPECT_EQ(in.header().findTypedAttribute<Imf::StringAttribute>("spectralLayoutVersion"), nullptr);
  fs::remove(path);
}

TEST(SpectralFilm, RgbChannelsCarryRec709PrimariesAndD65White) {
  RenderOptions options;
  options.beams = 10'000;
  options.device = DeviceChoice::Cpu;
  const RenderResult result = render(laserScene(), options);
  const fs::path path = writeTemp(result.image, "chromaticities");
  Imf::InputFile in(path.c_str());
  ASSERT_TRUE(Imf::hasChromaticities(in.header()));
  const Imf::Chromaticities& c = Imf::chromaticities(in.header());
  // Rec. 709 / sRGB primaries and D65 white (ITU-R BT.709, IEC 61966-2-1),
  // those the R, G, B channels are converted to.
  EXPECT_FLOAT_EQ(c.red.x, 0.64f);
  EXPECT_FLOAT_EQ(c.red.y, 0.33f);
  EXPECT_FLOAT_EQ(c.green.x, 0.30f);
  EXPECT_FLOAT_EQ(c.green.y, 0.60f);
  EXPECT_FLOAT_EQ(c.blue.x, 0.15f);
  EXPECT_FLOAT_EQ(c.blue.y, 0.06f);
  EXPECT_FLOAT_EQ(c.white.x, 0.3127f);
  EXPECT_FLOAT_EQ(c.white.y, 0.3290f);
  fs::remove(path);
}

TEST(SpectralFilm, SpectrumTimesBinWidthSumsToIrradiance) {
  Scene scene = bareSensorScene(0.008, 0.008, 8, 8, 47);
  scene.lights = {pointLight({0.0005, -0.0003, 0.01}, 1.0, makeBlackbodySpd(3000, 360, 830))};
  for (DeviceChoice device : {DeviceChoice::Cpu, DeviceChoice::Gpu}) {
    const RenderResult result = renderSpectral(scene, true, device);
    const RenderImage& image = result.image;
    const size_t bins = image.spectralBinCentresNm.size();
    ASSERT_EQ(bins, 47u);
    const double width = 470.0 / 47.0;
    size_t lit = 0;
    for (size_t p = 0; p < image.irradiance.size(); ++p) {
      double sum = 0.0;
      for (size_t b = 0; b < bins; ++b) sum += double(image.spectralIrradiance[p * bins + b]) * width;
      // Each channel and irradiance.E are the same double rounded once to
      // float (relative error <= 2^-24 ~ 6e-8 each), so 1e-6 is ample.
      EXPECT_NEAR(sum, double(image.irradiance[p]), 1e-6 * double(image.irradiance[p])) << "pixel " << p;
      lit += image.irradiance[p] > 0.0f;
    }
    EXPECT_GT(lit, 32u) << "the light should reach most of the sensor";
  }
}

TEST(SpectralFilm, LaserLineLandsInOneChannel) {
  const RenderResult result = renderSpectral(laserScene(), true);
  const RenderImage& image = result.image;
  const size_t bins = image.spectralBinCentresNm.size();
  ASSERT_EQ(bins, 94u);
  const size_t line = size_t((532.0 - 360.0) / 5.0);  // [530, 535) nm
  EXPECT_EQ(image.spectralBinCentresNm[line], 532.5);
  double power = 0.0;
  for (size_t p = 0; p < image.irradiance.size(); ++p) {
    for (size_t b = 0; b < bins; ++b) {
      if (b != line) {
        EXPECT_EQ(image.spectralIrradiance[p * bins + b], 0.0f) << "pixel " << p << " bin " << b;
      }
    }
    power += image.spectralIrradiance[p * bins + line];
  }
  EXPECT_GT(power, 0.0);
}

TEST(SpectralFilm, TrimmedAndFullSpectrumHaveTheSameChannels) {
  const Scene scene = laserScene();
  const RenderResult trimmed = renderSpectral(scene, true);
  const RenderResult full = renderSpectral(scene, false);
  EXPECT_LT(trimmed.plan.film.storedBins, full.plan.film.storedBins) << "the laser scene should trim its spectrum";
  const fs::path a = writeTemp(trimmed.image, "trimmed"), b = writeTemp(full.image, "full");
  EXPECT_EQ(channelNames(a), channelNames(b));
  fs::remove(a);
  fs::remove(b);
}

// error.E estimates the standard deviation of irradiance.E over renders with
// independent seeds. With K seeds, the sample variance s² of a pixel is
// σ² χ²(K-1)/(K-1) for normal errors (counts here are large), so s²/σ² has
// mean 1 and standard deviation sqrt(2/(K-1)). Over P lit pixels (nearly
// independent: a pixel holds a small share of the beams), the mean ratio
// has standard deviation sqrt(2/((K-1) P)); we allow 5 of those. Per pixel
// we allow 5 sqrt(2/(K-1)) as well, a looser check against one bad pixel.
void expectErrorMatchesSeedSpread(DeviceChoice choice) {
  Scene scene = bareSensorScene(0.008, 0.008, 8, 8, 16);
  scene.lights = {pointLight({0.0005, -0.0003, 0.01}, 1.0, makeBlackbodySpd(3000, 360, 830))};
  constexpr int K = 30;
  const auto device = Device::open(choice);
  const size_t pixels = 64;
  std::vector<double> sum(pixels, 0.0), sumSquares(pixels, 0.0), errorSquares(pixels, 0.0);
  for (int k = 0; k < K; ++k) {
    RenderOptions options;
    options.beams = 100'000;
    options.seed = 1000 + uint64_t(k);
    const RenderResult result = render(scene, options, *device);
    ASSERT_EQ(result.image.irradianceError.size(), pixels);
    for (size_t p = 0; p < pixels; ++p) {
      const double e = result.image.irradiance[p];
      sum[p] += e;
      sumSquares[p] += e * e;
      errorSquares[p] += double(result.image.irradianceError[p]) * result.image.irradianceError[p];
      if (e == 0.0) {
        EXPECT_EQ(result.image.irradianceError[p], 0.0f);
      }
    }
  }
  double ratioSum = 0.0;
  size_t lit = 0;
  const double perPixelSigma = std::sqrt(2.0 / (K - 1));
  for (size_t p = 0; p < pixels; ++p) {
    const double mean = sum[p] / K;
    const double sampleVariance = (sumSquares[p] - K * mean * mean) / (K - 1);
    const double estimatedVariance = errorSquares[p] / K;  // mean of error.E²
    if (!(estimatedVariance > 0.0)) continue;
    const double ratio = sampleVariance / estimatedVariance;
    EXPECT_NEAR(ratio, 1.0, 5.0 * perPixelSigma) << "pixel " << p;
    ratioSum += ratio;
    ++lit;
  }
  ASSERT_GT(lit, 32u);
  const double meanRatio = ratioSum / double(lit);
  ::testing::Test::RecordProperty("mean_variance_ratio", std::to_string(meanRatio));
  ::testing::Test::RecordProperty("lit_pixels", std::to_string(lit));
  EXPECT_NEAR(meanRatio, 1.0, 5.0 * perPixelSigma / std::sqrt(double(lit)))
      << "over " << lit << " pixels, s²/error.E² averages " << meanRatio;
}

TEST(SpectralFilm, ErrorChannelMatchesTheSpreadOfSeedsCpu) { expectErrorMatchesSeedSpread(DeviceChoice::Cpu); }
TEST(SpectralFilm, ErrorChannelMatchesTheSpreadOfSeedsGpu) { expectErrorMatchesSeedSpread(DeviceChoice::Gpu); }

}  // namespace
}  // namespace spectrace
