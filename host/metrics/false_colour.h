#pragma once
// A false-colour map of illuminance (spectrace measure --false-colour), as
// Radiance's falsecolor and lighting tools draw one: each pixel of the
// region in the colour of its band of lux, the isolux contours (the bands'
// boundaries) in black between them, and a legend giving each band's lux.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "metrics/illuminance_report.h"

namespace spectrace {

// Bands of equal width from 0 lux to topLux; the top band also holds
// values above topLux (a fixed --max-lux below the image's maximum). Ten
// bands of a legendTop give round boundaries (a tenth of 1, 2, 2.5 or 5
// times a power of ten).
struct FalseColourScale {
  double topLux = 1.0;
  int bands = 10;
};

// The legend's top for an image whose maximum is maxLux: the least of 1,
// 2, 2.5 and 5 times a power of ten at or above it (1 for an unlit image),
// so band boundaries are round numbers.
double legendTop(double maxLux);

// The band of a value: floor(lux / topLux * bands), at most bands - 1.
int bandOf(double lux, const FalseColourScale& scale);

// Band k's colour (of `bands`), from dark blue (0) to yellow (bands - 1):
// viridis, whose lightness rises steadily, so the order of the bands reads
// in grey too.
std::array<uint8_t, 3> bandColour(int band, int bands);

// The legend's text for band k: its lux range, "a-b" (the top band of a
// fixed scale: ">=a").
std::string bandLabel(int band, const FalseColourScale& scale, bool topIsOpen);

struct FalseColourImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  // 3 bytes a pixel, row-major from the top
  // The map's pixels: region pixel (x, y) is the square of side mapScale at
  // (x * mapScale, y * mapScale); the legend lies to the right of them.
  int mapScale = 1;
  int mapWidth = 0;
  int mapHeight = 0;
};

// The region's lux values (luxGrid's order) as a map with its legend.
// Small regions are enlarged by a whole factor (up to 8) so the map is at
// least 256 pixels on its longer side where that allows.
FalseColourImage falseColourMap(const std::vector<float>& lux, PixelRegion region, const FalseColourScale& scale,
                                bool topIsOpen);

}  // namespace spectrace
