// 8-bit sRGB PNG previews of RenderImage, written with libpng.
#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "io/image.h"

namespace spectrace {
namespace {

// IEC 61966-2-1 encoding of a linear value in [0, 1].
double srgbEncode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// Non-finite components count as black, both for exposure and for output.
float finiteOrZero(float v) { return std::isfinite(v) ? v : 0.0f; }

float pixelMax(const float* p) { return std::max({finiteOrZero(p[0]), finiteOrZero(p[1]), finiteOrZero(p[2])}); }

// Nearest-rank 99th percentile of max(R,G,B) over lit pixels (max > 0);
// 0 when nothing is lit. A percentile rather than the maximum keeps a few
// fireflies from darkening the whole preview.
float exposureLevel(const std::vector<float>& rgb) {
  std::vector<float> lit;
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    const float m = pixelMax(&rgb[i]);
    if (m > 0.0f) lit.push_back(m);
  }
  if (lit.empty()) return 0.0f;
  const std::size_t rank = (lit.size() * 99 + 99) / 100;  // ceil(0.99 n), 1-based
  const auto nth = lit.begin() + static_cast<std::ptrdiff_t>(rank - 1);
  std::nth_element(lit.begin(), nth, lit.end());
  return *nth;
}

std::uint8_t toByte(float v, float level) {
  // Divide (in double) rather than multiply by 1/level, so a value equal to
  // the level maps to exactly 1 and a tiny level cannot overflow.
  double x = static_cast<double>(finiteOrZero(v)) / static_cast<double>(level);
  x = std::clamp(x, 0.0, 1.0);
  return static_cast<std::uint8_t>(std::lround(srgbEncode(x) * 255.0));
}

// --- libpng glue -----------------------------------------------------------
// libpng reports errors by calling our error function, which must not
// return. It longjmps back to the setjmp in encodePng. Everything between
// (libpng's C frames, writeData, writeImage) has only trivially destructible
// locals, so no destructor is skipped; the error text goes into a fixed
// buffer for the same reason.

struct PngSink {
  int fd;
  std::uint64_t offset;
  char error[256];
};

void onPngError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->error, sizeof sink->error, "%s", message ? message : "libpng error");
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}  // a preview has nothing useful to warn about

void writeData(png_structp png, png_bytep data, size_t size) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  if (const int err = io_detail::pwriteAll(sink->fd, data, size, sink->offset)) {
    char message[160];
    std::snprintf(message, sizeof message, "write failed: %s", std::strerror(err));
    png_error(png, message);  // copies the message into the error buffer before longjmp
  }
  sink->offset += size;
}

void flushData(png_structp) {}  // pwrite is unbuffered; AtomicFile::commit() fsyncs

void writeImage(png_structp png, png_infop info, PngSink* sink, const std::uint8_t* pixels, int width, int height) {
  png_set_write_fn(png, sink, writeData, flushData);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // Tag the encoding so viewers do not reinterpret it.
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  const std::size_t rowBytes = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y) png_write_row(png, pixels + static_cast<std::size_t>(y) * rowBytes);
  png_write_end(png, info);
}

// Returns false with sink.error set on failure. Kept free of non-trivial
// locals and of variables modified after setjmp (-Wclobbered).
bool encodePng(PngSink& sink, const std::uint8_t* pixels, int width, int height) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, onPngError, onPngWarning);
  if (!png) {
    std::snprintf(sink.error, sizeof sink.error, "cannot create libpng write struct");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    std::snprintf(sink.error, sizeof sink.error, "cannot create libpng info struct");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  writeImage(png, info, &sink, pixels, width, height);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void writePngPreview(const std::filesystem::path& path, const RenderImage& image) {
  // Only rgb is used by the preview, so only it has to be consistent.
  if (image.width <= 0 || image.height <= 0) {
    throw ImageIoError("cannot write PNG " + path.string() + ": image size " + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + " is not positive");
  }
  const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  if (image.rgb.size() != pixels * 3) {
    throw ImageIoError("cannot write PNG " + path.string() + ": rgb has " + std::to_string(image.rgb.size()) +
                       " floats, expected " + std::to_string(pixels * 3) + " (" + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + "x3)");
  }

  std::vector<std::uint8_t> bytes(pixels * 3, 0);  // all black when nothing is lit
  if (const float level = exposureLevel(image.rgb); level > 0.0f) {
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = toByte(image.rgb[i], level);
  }
  writePngRgb8(path, image.width, image.height, bytes);
}

void writePngRgb8(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& bytes) {
  if (width <= 0 || height <= 0 || bytes.size() != std::size_t(width) * std::size_t(height) * 3)
    throw ImageIoError("cannot write PNG " + path.string() + ": " + std::to_string(bytes.size()) + " bytes for " +
                       std::to_string(width) + "x" + std::to_string(height) + " RGB pixels");
  io_detail::AtomicFile file(path, "PNG");
  PngSink sink{file.fd(), 0, {}};
  if (!encodePng(sink, bytes.data(), width, height)) file.fail(sink.error);
  file.commit();
}

}  // namespace spectrace
