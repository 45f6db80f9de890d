#include "film/develop.h"

#include "device_shared.h"

namespace spectrace {

RenderImage resolveOnCpu(const SpectralHistogram& histogram, const ResolveParameters& parameters) {
  RenderImage image;
  image.width = int(histogram.pixelsX);
  image.height = int(histogram.pixelsY);
  const size_t pixels = size_t(histogram.pixelsX) * histogram.pixelsY;
  image.rgb.resize(pixels * 3);
  image.xyz.resize(pixels * 3);
  image.irradiance.resize(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    glm::dvec3 xyz(0.0);
    uint64_t total = 0;
    for (uint32_t b = 0; b < histogram.bins; ++b) {
      const uint64_t c = histogram.counts[p * histogram.bins + b];
      total += c;
      const auto& w = parameters.binWeights[b];
      xyz += double(c) * glm::dvec3(w[0], w[1], w[2]);
    }
    xyz *= parameters.irradiancePerCount;
    if (parameters.useExactColour && histogram.hasExactColour()) {
      const double perBeam = parameters.irradiancePerCount * double(histogram.unitsPerBeam);
      const double perUnit = 683.0 * perBeam / double(device::kColourFixedPointScale);
      for (int k = 0; k < 3; ++k) xyz[k] = double(histogram.colourSums[p * 3 + k]) * perUnit;
    }
    const glm::dvec3 rgb = parameters.xyzToRgb * xyz;
    for (int k = 0; k < 3; ++k) {
      image.xyz[p * 3 + k] = float(xyz[k]);
      image.rgb[p * 3 + k] = float(rgb[k]);
    }
    image.irradiance[p] = float(double(total) * parameters.irradiancePerCount);
  }
  return image;
}

}  // namespace spectrace
