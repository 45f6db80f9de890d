#pragma once
// Lighting measurements of a render (spectrace measure), as a lighting
// engineer reads them: illuminance statistics over the sensor or a region
// of it, in lux from the image's XYZ.Y, and the per-pixel grid as CSV. The
// false-colour map is false_colour.h.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/image.h"

namespace spectrace {

// Refused input (a region, an image's values); the message names it.
struct MeasureError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// A rectangle of pixels: columns [x0, x1) and rows [y0, y1), rows counted
// from the top of the upright image (as the EXR stores them).
struct PixelRegion {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  uint64_t pixels() const { return uint64_t(width()) * uint64_t(height()); }
};

PixelRegion wholeImage(const RenderImage& image);

// "x0,y0,x1,y1" (--region) within an image of width x height: four
// integers with 0 <= x0 < x1 <= width and 0 <= y0 < y1 <= height. Throws
// MeasureError naming `option` and what is wrong.
PixelRegion parsePixelRegion(const std::string& text, int width, int height, const std::string& option = "--region");

// Illuminance over a region, in lux. U0 (min / mean) and Ud (min / max), the
// uniformity ratios of EN 12464-1, are absent where their divisor is 0 (no
// light at all).
struct IlluminanceStats {
  double minLux = 0.0;
  double maxLux = 0.0;
  double meanLux = 0.0;  // every pixel has the same area on the sensor
  std::optional<double> u0;
  std::optional<double> ud;
  uint64_t pixels = 0;
};

// The region's lux values (XYZ.Y), row by row from the top. Throws
// MeasureError for a value that is not finite or is negative, naming the
// pixel: no render makes one, so the file is not a render's.
std::vector<float> luxGrid(const RenderImage& image, PixelRegion region);

IlluminanceStats illuminanceStats(const std::vector<float>& lux);

// {"min_lux", "max_lux", "mean_lux", "u0", "ud", "pixels", "region"}; u0
// and ud are null where absent, region is [x0, y0, x1, y1].
std::string illuminanceJson(const IlluminanceStats& stats, PixelRegion region);

// The statistics as the command prints them, one per line.
std::string illuminanceText(const IlluminanceStats& stats, PixelRegion region);

// One line per row of the region, from the top; values comma-separated,
// with 9 significant digits, which give a float back exactly: a reader
// gets the EXR's values.
std::string luxCsv(const std::vector<float>& lux, PixelRegion region);

}  // namespace spectrace
