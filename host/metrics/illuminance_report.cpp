#include "metrics/illuminance_report.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace spectrace {

PixelRegion wholeImage(const RenderImage& image) { return PixelRegion{0, 0, image.width, image.height}; }

PixelRegion parsePixelRegion(const std::string& text, int width, int height, const std::string& option) {
  auto notFourIntegers = [&](const std::string& got) {
    return MeasureError(fmt::format("{} '{}': expected four integers x0,y0,x1,y1{}", option, text, got));
  };
  std::vector<long long> values;
  const char* p = text.data();
  const char* end = p + text.size();
  while (true) {
    long long v = 0;
    const auto [next, ec] = std::from_chars(p, end, v);
    if (ec != std::errc() || next == p) throw notFourIntegers("");
    values.push_back(v);
    p = next;
    if (p == end) break;
    if (*p != ',' || values.size() == 4) throw notFourIntegers("");
    ++p;
  }
  if (values.size() != 4) throw notFourIntegers(fmt::format(", got {}", values.size()));
  const long long x0 = values[0], y0 = values[1], x1 = values[2], y1 = values[3];
  if (!(0 <= x0 && x0 < x1 && x1 <= width) || !(0 <= y0 && y0 < y1 && y1 <= height))
    throw MeasureError(fmt::format("{} '{}': columns [x0, x1) and rows [y0, y1) must be non-empty and within the "
                                   "image's {} x {} pixels",
                                   option, text, width, height));
  return PixelRegion{int(x0), int(y0), int(x1), int(y1)};
}

std::vector<float> luxGrid(const RenderImage& image, PixelRegion region) {
  std::vector<float> lux;
  lux.reserve(region.pixels());
  for (int y = region.y0; y < region.y1; ++y) {
    for (int x = region.x0; x < region.x1; ++x) {
      const float value = image.xyz[(size_t(y) * size_t(image.width) + size_t(x)) * 3 + 1];
      if (!std::isfinite(value) || value < 0.0f)
        throw MeasureError(fmt::format("pixel ({}, {}) has XYZ.Y = {}: illuminance must be finite and not negative",
                                       x, y, value));
      lux.push_back(value);
    }
  }
  return lux;
}

IlluminanceStats illuminanceStats(const std::vector<float>& lux) {
  IlluminanceStats stats;
  if (lux.empty()) return stats;
  const auto [lo, hi] = std::minmax_element(lux.begin(), lux.end());
  stats.minLux = *lo;
  stats.maxLux = *hi;
  double sum = 0.0;
  for (float v : lux) sum += v;
  stats.pixels = lux.size();
  stats.meanLux = sum / double(lux.size());
  if (stats.meanLux > 0.0) stats.u0 = stats.minLux / stats.meanLux;
  if (stats.maxLux > 0.0) stats.ud = stats.minLux / stats.maxLux;
  return stats;
}

std::string illuminanceJson(const IlluminanceStats& stats, PixelRegion region) {
  nlohmann::ordered_json j;
  j["min_lux"] = stats.minLux;
  j["max_lux"] = stats.maxLux;
  j["mean_lux"] = stats.meanLux;
  j["u0"] = stats.u0 ? nlohmann::ordered_json(*stats.u0) : nlohmann::ordered_json(nullptr);
  j["ud"] = stats.ud ? nlohmann::ordered_json(*stats.ud) : nlohmann::ordered_json(nullptr);
  j["pixels"] = stats.pixels;
  j["region"] = {region.x0, region.y0, region.x1, region.y1};
  return j.dump(2) + "\n";
}

std::string illuminanceText(const IlluminanceStats& stats, PixelRegion region) {
  auto ratio = [](const std::optional<double>& r) {
    return r ? fmt::format("{:.4f}", *r) : std::string("undefined (no light)");
  };
  return fmt::format(
      "illuminance over columns [{}, {}) and rows [{}, {}) ({} pixels):\n"
      "  min  {:.6g} lx\n  max  {:.6g} lx\n  mean {:.6g} lx\n  U0 = min/mean {}\n  Ud = min/max  {}\n",
      region.x0, region.x1, region.y0, region.y1, stats.pixels, stats.minLux, stats.maxLux, stats.meanLux,
      ratio(stats.u0), ratio(stats.ud));
}

std::string luxCsv(const std::vector<float>& lux, PixelRegion region) {
  std::string csv;
  csv.reserve(lux.size() * 14);
  size_t k = 0;
  for (int y = 0; y < region.height(); ++y) {
    for (int x = 0; x < region.width(); ++x, ++k) {
      if (x > 0) csv += ',';
      csv += fmt::format("{:.9g}", lux[k]);
    }
    csv += '\n';
  }
  return csv;
}

}  // namespace spectrace
