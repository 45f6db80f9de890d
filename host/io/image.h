#pragma once
// Rendered images and their files: OpenEXR (float32) and PNG previews.
#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace spectrace {

// Per-pixel results of a render, row-major with row 0 at the top of the
// upright image.
struct RenderImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;         // 3 per pixel, linear sRGB, may be negative
  std::vector<float> xyz;         // 3 per pixel, CIE XYZ, Y in lux
  std::vector<float> irradiance;  // 1 per pixel, W/m² summed over all bins
};

// Header attributes. Strings hold exact values (e.g. 64-bit beam counts).
struct ImageMetadata {
  std::map<std::string, std::string> strings;
  std::map<std::string, double> numbers;
};

struct ImageIoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Channels: R, G, B (linear sRGB), XYZ.X, XYZ.Y, XYZ.Z, irradiance.E.
// Written to a temporary file beside `path` and renamed, so an interrupted
// write never leaves a truncated image.
void writeExr(const std::filesystem::path& path, const RenderImage& image, const ImageMetadata& meta);
struct ExrContents {
  RenderImage image;
  ImageMetadata meta;
};
ExrContents readExr(const std::filesystem::path& path);

// 8-bit sRGB preview: negative components clipped, automatic exposure maps
// the 99th percentile of per-pixel max(R,G,B) among lit pixels to 1, then
// the sRGB transfer curve. Also atomic (temp file + rename).
void writePngPreview(const std::filesystem::path& path, const RenderImage& image);

}  // namespace spectrace
