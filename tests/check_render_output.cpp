// Checks a rendered EXR for the whole-program tests: it reads back, has the
// expected size and header, and every pixel's irradiance and XYZ are finite
// and non-negative (RGB may be negative: out-of-gamut sRGB), and so is its
// error estimate error.E. With SPECTRAL_BINS, the file must also hold that
// many spectral channels (S0.<nm>nm), the spectral layout's attributes, and
// spectra that sum to the irradiance. Exit 0 on success; otherwise prints
// what is wrong.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "io/image.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: check_render_output FILE.exr [MIN_LIT_PIXELS [SPECTRAL_BINS]]\n");
    return 2;
  }
  const long minLit = argc > 2 ? std::atol(argv[2]) : 1;
  const long spectralBins = argc > 3 ? std::atol(argv[3]) : -1;  // -1: not checked
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
    if (image.irradianceError.size() != image.irradiance.size()) {
      std::fprintf(stderr, "%s: channel error.E is missing\n", argv[1]);
      return 1;
    }
    for (size_t p = 0; p < image.irradianceError.size(); ++p) {
      const float sigma = image.irradianceError[p];
      if (!std::isfinite(sigma) || sigma < 0.0f || (image.irradiance[p] == 0.0f && sigma != 0.0f)) {
        std::fprintf(stderr, "%s: pixel %zu has error.E %g (irradiance %g)\n", argv[1], p, sigma, image.irradiance[p]);
        return 1;
      }
    }
    if (spectralBins >= 0) {
      const size_t bins = image.spectralBinCentresNm.size();
      if (long(bins) != spectralBins) {
        std::fprintf(stderr, "%s: %zu spectral channels, expected %ld\n", argv[1], bins, spectralBins);
        return 1;
      }
      const auto version = contents.meta.strings.find("spectralLayoutVersion");
      const auto units = contents.meta.strings.find("emissiveUnits");
      if (version == contents.meta.strings.end() || version->second != "1.0" || units == contents.meta.strings.end() ||
          units->second != "W.m^-2.nm^-1") {
        std::fprintf(stderr, "%s: spectralLayoutVersion or emissiveUnits missing or wrong\n", argv[1]);
        return 1;
      }
      // Equal-width bins: the width is the spacing of the centres.
      const double width = bins > 1 ? image.spectralBinCentresNm[1] - image.spectralBinCentresNm[0] : 0.0;
      for (size_t p = 0; p < image.irradiance.size(); ++p) {
        double sum = 0.0;
        for (size_t b = 0; b < bins; ++b) sum += double(image.spectralIrradiance[p * bins + b]) * width;
        // Channel names hold 6 decimals of nm, so the width read back is
        // exact to ~1e-6 nm; 1e-5 relative covers it and float rounding.
        if (std::abs(sum - double(image.irradiance[p])) > 1e-5 * double(image.irradiance[p])) {
          std::fprintf(stderr, "%s: pixel %zu: spectrum sums to %.9g, irradiance.E is %.9g\n", argv[1], p, sum,
                       double(image.irradiance[p]));
          return 1;
        }
      }
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
