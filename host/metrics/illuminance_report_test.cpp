// spectrace measure's computations: statistics, grid, region, false-colour
// map, checked against values computed here from the image (and, through
// an EXR written and read back, from the file).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "metrics/false_colour.h"
#include "metrics/illuminance_report.h"

namespace spectrace {
namespace {

// A width x height image whose XYZ.Y is y(x, row); the other channels are
// zero but sized, as writeExr wants.
template <typename F>
RenderImage imageWithY(int width, int height, F y) {
  RenderImage image;
  image.width = width;
  image.height = height;
  const size_t pixels = size_t(width) * size_t(height);
  image.rgb.assign(pixels * 3, 0.0f);
  image.xyz.assign(pixels * 3, 0.0f);
  image.irradiance.assign(pixels, 0.0f);
  for (int row = 0; row < height; ++row)
    for (int x = 0; x < width; ++x) image.xyz[(size_t(row) * size_t(width) + size_t(x)) * 3 + 1] = y(x, row);
  return image;
}

TEST(PixelRegion, ParsesFourIntegersWithinTheImage) {
  const PixelRegion r = parsePixelRegion("1,2,5,7", 8, 9);
  EXPECT_EQ(r.x0, 1);
  EXPECT_EQ(r.y0, 2);
  EXPECT_EQ(r.x1, 5);
  EXPECT_EQ(r.y1, 7);
  EXPECT_EQ(r.pixels(), 20u);
  const PixelRegion whole = parsePixelRegion("0,0,8,9", 8, 9);
  EXPECT_EQ(whole.pixels(), 72u);
}

TEST(PixelRegion, RefusesWhatIsNotAFittingRectangle) {
  for (const char* bad : {"", "1,2,3", "1,2,3,4,5", "1,2,3,x", "1.5,2,3,4", "1,,3,4", "1,2,3,4,", " 1,2,3,4",
                          "3,2,3,4", "1,4,3,4", "-1,0,3,4", "0,0,9,4", "0,0,3,10", "5,0,3,4"}) {
    try {
      parsePixelRegion(bad, 8, 9);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const MeasureError& e) {
      EXPECT_NE(std::string(e.what()).find("--region '" + std::string(bad) + "'"), std::string::npos) << e.what();
    }
  }
}

TEST(IlluminanceStats, MatchesTheRegionsValues) {
  const RenderImage image = imageWithY(4, 3, [](int x, int row) { return float(x + 10 * row); });
  const PixelRegion region{1, 0, 3, 2};  // Y = 1, 2, 11, 12
  const std::vector<float> lux = luxGrid(image, region);
  ASSERT_EQ(lux, (std::vector<float>{1.0f, 2.0f, 11.0f, 12.0f}));
  const IlluminanceStats s = illuminanceStats(lux);
  EXPECT_EQ(s.minLux, 1.0);
  EXPECT_EQ(s.maxLux, 12.0);
  EXPECT_EQ(s.meanLux, 6.5);
  ASSERT_TRUE(s.u0 && s.ud);
  EXPECT_EQ(*s.u0, 1.0 / 6.5);
  EXPECT_EQ(*s.ud, 1.0 / 12.0);
  EXPECT_EQ(s.pixels, 4u);
}

TEST(IlluminanceStats, UniformityIsUndefinedWithoutLight) {
  const RenderImage image = imageWithY(3, 2, [](int, int) { return 0.0f; });
  const IlluminanceStats s = illuminanceStats(luxGrid(image, wholeImage(image)));
  EXPECT_EQ(s.maxLux, 0.0);
  EXPECT_FALSE(s.u0);
  EXPECT_FALSE(s.ud);
  const nlohmann::json j = nlohmann::json::parse(illuminanceJson(s, wholeImage(image)));
  EXPECT_TRUE(j.at("u0").is_null());
  EXPECT_TRUE(j.at("ud").is_null());
  EXPECT_EQ(j.at("pixels").get<uint64_t>(), 6u);
}

TEST(IlluminanceStats, RefusesValuesNoRenderMakesNamingThePixel) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), -1.0f}) {
    const RenderImage image = imageWithY(4, 3, [&](int x, int row) { return x == 2 && row == 1 ? bad : 1.0f; });
    try {
      luxGrid(image, wholeImage(image));
      ADD_FAILURE() << "accepted " << bad;
    } catch (const MeasureError& e) {
      EXPECT_NE(std::string(e.what()).find("pixel (2, 1)"), std::string::npos) << e.what();
    }
    // A region without that pixel is measured.
    EXPECT_EQ(luxGrid(image, PixelRegion{0, 0, 2, 3}).size(), 6u);
  }
}

// Through a file: the EXR's own values, read back, give the JSON's figures
// and the CSV's grid exactly.
TEST(IlluminanceReport, JsonAndCsvCarryTheExrsValues) {
  std::mt19937 random(11);
  const RenderImage written = imageWithY(7, 5, [&](int, int) {
    return float(random() >> 8) * 0x1p-24f * 300.0f;  // up to 300 lux, all 24 bits of mantissa in play
  });
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "illuminance_report_test";
  std::filesystem::create_directories(dir);
  writeExr(dir / "lit.exr", written, {});
  const RenderImage image = readExr(dir / "lit.exr").image;
  const PixelRegion region = parsePixelRegion("2,1,6,5", image.width, image.height);
  const std::vector<float> lux = luxGrid(image, region);

  double lo = 1e300, hi = -1e300, sum = 0.0;
  for (int row = region.y0; row < region.y1; ++row)
    for (int x = region.x0; x < region.x1; ++x) {
      const double v = image.xyz[(size_t(row) * 7 + size_t(x)) * 3 + 1];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      sum += v;
    }
  const nlohmann::json j = nlohmann::json::parse(illuminanceJson(illuminanceStats(lux), region));
  EXPECT_EQ(j.at("min_lux").get<double>(), lo);
  EXPECT_EQ(j.at("max_lux").get<double>(), hi);
  EXPECT_NEAR(j.at("mean_lux").get<double>(), sum / 16.0, 1e-12 * hi);  // the same sum in another order
  EXPECT_NEAR(j.at("u0").get<double>(), lo / (sum / 16.0), 1e-12);
  EXPECT_EQ(j.at("ud").get<double>(), lo / hi);
  EXPECT_EQ(j.at("pixels").get<uint64_t>(), 16u);
  EXPECT_EQ(j.at("region"), nlohmann::json({2, 1, 6, 5}));

  std::istringstream csv(luxCsv(lux, region));
  std::string line;
  int row = region.y0;
  for (; std::getline(csv, line); ++row) {
    std::istringstream cells(line);
    std::string cell;
    int x = region.x0;
    for (; std::getline(cells, cell, ','); ++x)
      EXPECT_EQ(std::strtof(cell.c_str(), nullptr), image.xyz[(size_t(row) * 7 + size_t(x)) * 3 + 1])
          << "row " << row << " column " << x;
    EXPECT_EQ(x, region.x1);
  }
  EXPECT_EQ(row, region.y1);
  std::filesystem::remove_all(dir);
}

TEST(FalseColour, LegendTopIsTheNextRoundNumber) {
  const std::pair<double, double> cases[] = {{0.0, 1.0},    {1.0, 1.0},     {1.01, 2.0},  {2.0, 2.0},
                                             {2.2, 2.5},    {3.0, 5.0},     {7.0, 10.0},  {10.0, 10.0},
                                             {0.03, 0.05},  {1234.0, 2000}, {100.0, 100}, {1000.0, 1000},
                                             {0.001, 0.001}, {4.9e5, 5e5}};
  for (const auto& [max, top] : cases) EXPECT_NEAR(legendTop(max), top, 1e-12 * top) << "max " << max;
  // Always at or above the maximum, and under twice it.
  std::mt19937 random(5);
  for (int i = 0; i < 2000; ++i) {
    const double max = std::pow(10.0, 12.0 * (double(random()) * 0x1p-32 - 0.5));
    const double top = legendTop(max);
    EXPECT_GE(top, max);
    EXPECT_LT(top, 2.0 * max);
  }
}

TEST(FalseColour, BandsSplitTheScaleEvenly) {
  const FalseColourScale scale{500.0, 10};
  EXPECT_EQ(bandOf(0.0, scale), 0);
  EXPECT_EQ(bandOf(49.9, scale), 0);
  EXPECT_EQ(bandOf(50.0, scale), 1);
  EXPECT_EQ(bandOf(499.0, scale), 9);
  EXPECT_EQ(bandOf(500.0, scale), 9);
  EXPECT_EQ(bandOf(1e9, scale), 9);
  EXPECT_EQ(bandLabel(0, scale, false), "0-50");
  EXPECT_EQ(bandLabel(3, scale, false), "150-200");
  EXPECT_EQ(bandLabel(9, scale, false), "450-500");
  EXPECT_EQ(bandLabel(9, scale, true), ">=450");
  EXPECT_EQ(bandLabel(7, FalseColourScale{2.5, 10}, false), "1.75-2");
  EXPECT_EQ(bandLabel(9, FalseColourScale{1e6, 10}, false), "900000-1000000");
  EXPECT_EQ(bandLabel(1, FalseColourScale{0.05, 10}, false), "0.005-0.01");
  // Colours run from dark to light, every band its own.
  for (int b = 1; b < 10; ++b) {
    const auto lo = bandColour(b - 1, 10), hi = bandColour(b, 10);
    EXPECT_LT(0.2126 * lo[0] + 0.7152 * lo[1] + 0.0722 * lo[2], 0.2126 * hi[0] + 0.7152 * hi[1] + 0.0722 * hi[2]);
  }
}

// The map: each pixel in its band's colour, a contour where the band
// changes, and the legend's swatches in the band colours.
TEST(FalseColour, MapShowsBandsContoursAndLegend) {
  // Columns 0-1 in band 2, column 2 in band 7 (of 10 up to 100 lux).
  const RenderImage image = imageWithY(3, 2, [](int x, int) { return x < 2 ? 25.0f : 75.0f; });
  const std::vector<float> lux = luxGrid(image, wholeImage(image));
  const IlluminanceStats stats = illuminanceStats(lux);
  const FalseColourScale scale{legendTop(stats.maxLux), 10};
  ASSERT_EQ(scale.topLux, 100.0);
  const FalseColourImage map = falseColourMap(lux, wholeImage(image), scale, false);
  ASSERT_EQ(map.mapScale, 8);  // 3 pixels enlarged towards 256, at most 8 times
  ASSERT_EQ(map.mapWidth, 24);
  ASSERT_EQ(map.mapHeight, 16);
  ASSERT_EQ(map.rgb.size(), size_t(map.width) * size_t(map.height) * 3);
  auto at = [&](int x, int y) {
    const size_t i = (size_t(y) * size_t(map.width) + size_t(x)) * 3;
    return std::array<uint8_t, 3>{map.rgb[i], map.rgb[i + 1], map.rgb[i + 2]};
  };
  EXPECT_EQ(at(3, 3), bandColour(2, 10));
  EXPECT_EQ(at(11, 3), bandColour(2, 10));  // inside pixel 1, away from its edges
  EXPECT_EQ(at(20, 12), bandColour(7, 10));
  EXPECT_EQ(at(15, 4), (std::array<uint8_t, 3>{0, 0, 0}));   // pixel 1's right edge: the contour
  EXPECT_EQ(at(7, 4), bandColour(2, 10));                     // no contour inside band 2
  // The legend's swatches, top band first, below the title row.
  for (int row = 0; row < 10; ++row)
    EXPECT_EQ(at(map.mapWidth + 8 + 7, 8 + (row + 1) * 16 + 7), bandColour(9 - row, 10));
}

}  // namespace
}  // namespace spectrace
