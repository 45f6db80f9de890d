// Checks a rendered EXR for the whole-program tests: it reads back, has the
// expected size and header, and every pixel's irradiance and XYZ are finite
// and non-negative (RGB may be negative: out-of-gamut sRGB). Exit 0 on
// success; otherwise prints what is wrong.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "io/image.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: check_render_output FILE.exr [MIN_LIT_PIXELS]\n");
    return 2;
  }
  const long minLit = argc > 2 ? std::atol(argv[2]) : 1;
  try {
    const auto contents = spectrace::readExr(argv[1]);
    const auto& image = contents.image;
    long lit = 0;
    for (size_t p = 0; p < image.irradiance.size(); ++p) {
      const float e = image.irradiance[p];
      if (!std::isfinite(e) || e < 0.0f) {
        std::fprintf(stderr, "%s: pixel %zu has irradiance %g\n", argv[1], p, e);
        return 1;
      }
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(image.xyz[p * 3 + k]) || image.xyz[p * 3 + k] < 0.0f || !std::isfinite(image.rgb[p * 3 + k])) {
          std::fprintf(stderr, "%s: pixel %zu has a bad colour value\n", argv[1], p);
          return 1;
        }
      }
      lit += e > 0.0f;
    }
    for (const char* key : {"spectrace:beams", "spectrace:seed", "spectrace:device", "spectrace:scene_sha256"}) {
      if (!contents.meta.strings.count(key)) {
        std::fprintf(stderr, "%s: header attribute %s is missing\n", argv[1], key);
        return 1;
      }
    }
    if (!contents.meta.numbers.count("spectrace:wall_time_s")) {
      std::fprintf(stderr, "%s: header attribute spectrace:wall_time_s is missing\n", argv[1]);
      return 1;
    }
    if (lit < minLit) {
      std::fprintf(stderr, "%s: only %ld lit pixels, expected at least %ld\n", argv[1], lit, minLit);
      return 1;
    }
    std::printf("%s: %dx%d, %ld lit pixels, beams %s, device %s\n", argv[1], image.width, image.height, lit,
                contents.meta.strings.at("spectrace:beams").c_str(), contents.meta.strings.at("spectrace:device").c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
