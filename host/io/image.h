#pragma once
// Rendered images and their files: OpenEXR (float32) and PNG previews.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
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
  // 1 per pixel, W/m²: the estimated standard error of `irradiance`; empty
  // when unknown (then no error.E channel is written).
  std::vector<float> irradianceError;
  // Optional spectral block: the bin centres (nm) and, per pixel, one
  // spectral irradiance per bin (W m⁻² nm⁻¹, [pixel][bin]). Empty: none.
  std::vector<double> spectralBinCentresNm;
  std::vector<float> spectralIrradiance;
};

// Header attributes. Strings hold exact values (e.g. 64-bit beam counts).
struct ImageMetadata {
  std::map<std::string, std::string> strings;
  std::map<std::string, double> numbers;
};

struct ImageIoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Channels: R, G, B (linear sRGB), XYZ.X, XYZ.Y, XYZ.Z, irradiance.E; and
// error.E when the image has irradianceError; and with a spectral block,
// one channel per bin in the spectral OpenEXR layout of Fichet, Pacanowski
// and Wilkie (JCGT 10(3), 2021): "S0.<nm>nm" (spectralChannelName), with
// the header attributes spectralLayoutVersion = "1.0" and emissiveUnits =
// "W.m^-2.nm^-1". The standard chromaticities attribute gives R, G, B's
// Rec. 709 primaries and D65 white.
// Written to a temporary file beside `path` and renamed, so an interrupted
// write never leaves a truncated image.
void writeExr(const std::filesystem::path& path, const RenderImage& image, const ImageMetadata& meta);
// "S0.552,500000nm" for 552.5: the layout's name of an emissive (Stokes 0)
// channel at that wavelength, a comma as decimal separator, 6 decimals.
std::string spectralChannelName(double wavelengthNm);
// Two bins whose centres give one channel name: with 6 decimals, bins about
// 1e-6 nm apart do. A file cannot hold both, so writers check before tracing.
struct SpectralChannelClash {
  std::size_t first = 0, second = 0;  // bin indices, first < second
  std::string name;
};
// The clash of the lowest second bin, or none when every name is distinct.
std::optional<SpectralChannelClash> spectralChannelClash(const std::vector<double>& centresNm);
struct ExrContents {
  RenderImage image;
  ImageMetadata meta;
};
ExrContents readExr(const std::filesystem::path& path);

// 8-bit sRGB preview: negative components clipped, automatic exposure maps
// the 99th percentile of per-pixel max(R,G,B) among lit pixels to 1, then
// the sRGB transfer curve. Also atomic (temp file + rename).
void writePngPreview(const std::filesystem::path& path, const RenderImage& image);

// An 8-bit sRGB PNG of `width` x `height` pixels, 3 bytes each, row-major
// from the top (a false-colour map). Atomic, as above.
void writePngRgb8(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& bytes);

// A text file (JSON, CSV), written atomically as the images are; `what`
// names the format in messages.
void writeTextFile(const std::filesystem::path& path, const std::string& text, const char* what);

}  // namespace spectrace
