#include "metrics/false_colour.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace spectrace {
namespace {

// Every 32nd entry of matplotlib's viridis table (van der Walt and Smith,
// CC0), and its last; bands take colours between them linearly.
constexpr std::array<std::array<double, 3>, 9> kViridis = {{{0.267004, 0.004874, 0.329415},
                                                            {0.282623, 0.140926, 0.457517},
                                                            {0.229739, 0.322361, 0.545706},
                                                            {0.172719, 0.448791, 0.557885},
                                                            {0.127568, 0.566949, 0.550556},
                                                            {0.134692, 0.658636, 0.517649},
                                                            {0.369214, 0.788888, 0.382914},
                                                            {0.678489, 0.863742, 0.189503},
                                                            {0.993248, 0.906157, 0.143936}}};

// A 5 x 7 pixel font for the legend's labels: written here because the
// legend needs a dozen characters, where a font library would bring a font
// file and a rasteriser. Rows from the top; '#' is ink.
struct Glyph {
  char c;
  const char* rows[7];
};
constexpr Glyph kGlyphs[] = {
    {'0', {" ### ", "#   #", "#  ##", "# # #", "##  #", "#   #", " ### "}},
    {'1', {"  #  ", " ##  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### "}},
    {'2', {" ### ", "#   #", "    #", "   # ", "  #  ", " #   ", "#####"}},
    {'3', {"#####", "   # ", "  #  ", "   # ", "    #", "#   #", " ### "}},
    {'4', {"   # ", "  ## ", " # # ", "#  # ", "#####", "   # ", "   # "}},
    {'5', {"#####", "#    ", "#### ", "    #", "    #", "#   #", " ### "}},
    {'6', {"  ## ", " #   ", "#    ", "#### ", "#   #", "#   #", " ### "}},
    {'7', {"#####", "    #", "   # ", "  #  ", " #   ", " #   ", " #   "}},
    {'8', {" ### ", "#   #", "#   #", " ### ", "#   #", "#   #", " ### "}},
    {'9', {" ### ", "#   #", "#   #", " ####", "    #", "   # ", " ##  "}},
    {'.', {"     ", "     ", "     ", "     ", "     ", " ##  ", " ##  "}},
    {'-', {"     ", "     ", "     ", " ### ", "     ", "     ", "     "}},
    {'+', {"     ", "  #  ", "  #  ", "#####", "  #  ", "  #  ", "     "}},
    {'>', {" #   ", "  #  ", "   # ", "    #", "   # ", "  #  ", " #   "}},
    {'=', {"     ", "     ", "#####", "     ", "#####", "     ", "     "}},
    {'e', {"     ", "     ", " ### ", "#   #", "#####", "#    ", " ### "}},
    {'l', {" ##  ", "  #  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### "}},
    {'u', {"     ", "     ", "#   #", "#   #", "#   #", "#  ##", " ## #"}},
    {'x', {"     ", "     ", "#   #", " # # ", "  #  ", " # # ", "#   #"}},
    {' ', {"     ", "     ", "     ", "     ", "     ", "     ", "     "}},
};
constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;

const Glyph* glyphOf(char c) {
  for (const Glyph& g : kGlyphs)
    if (g.c == c) return &g;
  return nullptr;
}

struct Canvas {
  int width, height;
  std::vector<uint8_t>& rgb;
  void set(int x, int y, std::array<uint8_t, 3> c) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    const size_t i = (size_t(y) * size_t(width) + size_t(x)) * 3;
    rgb[i] = c[0];
    rgb[i + 1] = c[1];
    rgb[i + 2] = c[2];
  }
  void fill(int x0, int y0, int w, int h, std::array<uint8_t, 3> c) {
    for (int y = y0; y < y0 + h; ++y)
      for (int x = x0; x < x0 + w; ++x) set(x, y, c);
  }
  void text(int x, int y, const std::string& s) {
    for (char c : s) {
      if (const Glyph* g = glyphOf(c)) {
        for (int row = 0; row < kGlyphHeight; ++row)
          for (int col = 0; col < kGlyphWidth; ++col)
            if (g->rows[row][col] == '#') set(x + col, y + row, {0, 0, 0});
      }
      x += kGlyphAdvance;
    }
  }
};

// A band boundary in lux: whole numbers in full (1000000, not 1e+06), others
// to six digits, which drop the rounding of k * width.
std::string luxText(double lux) {
  const double whole = std::round(lux);
  if (std::abs(lux - whole) <= 1e-9 * std::max(1.0, whole) && whole < 1e12) return fmt::format("{:.0f}", whole);
  return fmt::format("{:.6g}", lux);
}

constexpr std::array<uint8_t, 3> kBlack = {0, 0, 0};
constexpr int kSwatch = 14;       // a band's swatch, and its row's height
constexpr int kRowHeight = 16;
constexpr int kLegendMargin = 8;  // between the map and the legend, and round it

}  // namespace

double legendTop(double maxLux) {
  if (!(maxLux > 0.0)) return 1.0;
  double decade = std::pow(10.0, std::floor(std::log10(maxLux)));
  // log10 may land a hair off for exact powers of ten: step back into range.
  if (decade > maxLux) decade /= 10.0;
  for (double step : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (step * decade >= maxLux) return step * decade;
  return 10.0 * decade;
}

int bandOf(double lux, const FalseColourScale& scale) {
  const double x = std::floor(lux / scale.topLux * scale.bands);
  return int(std::clamp(x, 0.0, double(scale.bands - 1)));
}

std::array<uint8_t, 3> bandColour(int band, int bands) {
  const double t = bands > 1 ? double(band) / double(bands - 1) : 0.0;
  const double at = t * double(kViridis.size() - 1);
  const size_t i = std::min(size_t(at), kViridis.size() - 2);
  const double f = at - double(i);
  std::array<uint8_t, 3> c{};
  for (int k = 0; k < 3; ++k)
    c[size_t(k)] = uint8_t(std::lround(255.0 * (kViridis[i][size_t(k)] * (1.0 - f) + kViridis[i + 1][size_t(k)] * f)));
  return c;
}

std::string bandLabel(int band, const FalseColourScale& scale, bool topIsOpen) {
  const double width = scale.topLux / scale.bands;
  if (topIsOpen && band == scale.bands - 1) return ">=" + luxText(width * band);
  return luxText(width * band) + "-" + luxText(width * (band + 1));
}

FalseColourImage falseColourMap(const std::vector<float>& lux, PixelRegion region, const FalseColourScale& scale,
                                bool topIsOpen) {
  FalseColourImage image;
  const int longer = std::max(region.width(), region.height());
  image.mapScale = std::clamp(256 / std::max(longer, 1), 1, 8);
  image.mapWidth = region.width() * image.mapScale;
  image.mapHeight = region.height() * image.mapScale;
  size_t labelChars = 3;  // "lux"
  for (int b = 0; b < scale.bands; ++b) labelChars = std::max(labelChars, bandLabel(b, scale, topIsOpen).size());
  const int legendWidth = kLegendMargin + kSwatch + 4 + int(labelChars) * kGlyphAdvance + kLegendMargin;
  const int legendHeight = kLegendMargin + (scale.bands + 1) * kRowHeight + kLegendMargin;
  image.width = image.mapWidth + legendWidth;
  image.height = std::max(image.mapHeight, legendHeight);
  image.rgb.assign(size_t(image.width) * size_t(image.height) * 3, 255);
  Canvas canvas{image.width, image.height, image.rgb};

  const int w = region.width(), h = region.height(), s = image.mapScale;
  auto band = [&](int x, int y) { return bandOf(lux[size_t(y) * size_t(w) + size_t(x)], scale); };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int b = band(x, y);
      canvas.fill(x * s, y * s, s, s, bandColour(b, scale.bands));
      // Isolux contours: the edge of a pixel whose right or lower
      // neighbour lies in another band.
      if (x + 1 < w && band(x + 1, y) != b) canvas.fill(x * s + s - 1, y * s, 1, s, kBlack);
      if (y + 1 < h && band(x, y + 1) != b) canvas.fill(x * s, y * s + s - 1, s, 1, kBlack);
    }
  }

  // The legend: "lux", then the bands from the top one down.
  const int left = image.mapWidth + kLegendMargin;
  canvas.text(left, kLegendMargin + (kRowHeight - kGlyphHeight) / 2, "lux");
  for (int row = 0; row < scale.bands; ++row) {
    const int b = scale.bands - 1 - row;
    const int top = kLegendMargin + (row + 1) * kRowHeight;
    canvas.fill(left, top, kSwatch, kSwatch, bandColour(b, scale.bands));
    canvas.text(left + kSwatch + 4, top + (kSwatch - kGlyphHeight) / 2, bandLabel(b, scale, topIsOpen));
  }
  return image;
}

}  // namespace spectrace
