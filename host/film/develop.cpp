#include "film/develop.h"

#include <cmath>

#include "device_shared.h"
#include "film/pixel_variance.h"

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

std::vector<float> developSpectrum(const SpectralHistogram& histogram, const ResolveParameters& parameters,
                                   double binWidthNm) {
  const double perCount = parameters.irradiancePerCount / binWidthNm;
  std::vector<float> spectrum(histogram.counts.size());
  for (size_t i = 0; i < spectrum.size(); ++i) spectrum[i] = float(double(histogram.counts[i]) * perCount);
  return spectrum;
}

std::vector<double> binCentresNm(double lambdaMinNm, double lambdaMaxNm, uint32_t bins) {
  std::vector<double> centres(bins);
  const double width = (lambdaMaxNm - lambdaMinNm) / double(bins);
  for (uint32_t b = 0; b < bins; ++b) centres[b] = lambdaMinNm + (double(b) + 0.5) * width;
  return centres;
}

std::vector<float> developIrradianceError(const SpectralHistogram& histogram, const ResolveParameters& parameters,
                                          uint64_t beams) {
  const size_t pixels = size_t(histogram.pixelsX) * histogram.pixelsY;
  std::vector<float> error(pixels, 0.0f);
  if (beams == 0) return error;
  const std::vector<double> relativeVariance = estimatedRelativeVariance(histogram, beams);
  for (size_t p = 0; p < pixels; ++p) {
    if (!std::isfinite(relativeVariance[p])) continue;  // no counts: no irradiance and no estimate
    uint64_t total = 0;
    for (uint32_t b = 0; b < histogram.bins; ++b) total += histogram.counts[p * histogram.bins + b];
    const double irradiance = double(total) * parameters.irradiancePerCount;
    error[p] = float(std::sqrt(relativeVariance[p]) * irradiance);
  }
  return error;
}

}  // namespace spectrace
