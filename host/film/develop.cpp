#include "film/develop.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "device_shared.h"
#include "film/pixel_variance.h"
#include "kernel_lang.h"

namespace spectrace {

namespace {

RenderImage blankImage(uint32_t pixelsX, uint32_t pixelsY, bool withError) {
  RenderImage image;
  image.width = int(pixelsX);
  image.height = int(pixelsY);
  const size_t pixels = size_t(pixelsX) * pixelsY;
  image.rgb.assign(pixels * 3, 0.0f);
  image.xyz.assign(pixels * 3, 0.0f);
  image.irradiance.assign(pixels, 0.0f);
  if (withError) image.irradianceError.assign(pixels, 0.0f);
  return image;
}

// One pixel's counters, wherever they live: its counts of the factors' bins
// from firstBin (the others are 0), its X, Y, Z colour sums (or null) and
// its squared-weight sum.
struct PixelCounters {
  const uint64_t* counts;
  uint32_t firstBin;
  const uint64_t* colourSums;
  uint64_t squaredWeights;
};

// The shared resolve (shaders/resolve_pixel.h) in double over host counters.
namespace host_resolve {
using namespace device;
using std::max;
using glm::dot;
struct HostPixel {
  const uint64_t* counts;
  const uint64_t* colourSums;
  const std::array<double, 3>* binWeights;  // from the pixel's first bin
};
#define RESOLVE_REAL double
#define RESOLVE_VEC3 glm::dvec3
#define RESOLVE_PIXEL const HostPixel&
inline uint64_t resolveBinCount(const HostPixel& pixel, uint bin) { return pixel.counts[bin]; }
inline uint64_t resolveColourSum(const HostPixel& pixel, uint k) { return pixel.colourSums[k]; }
inline glm::dvec3 resolveBinWeight(const HostPixel& pixel, uint bin) {
  const auto& w = pixel.binWeights[bin];
  return glm::dvec3(w[0], w[1], w[2]);
}
#include "resolve_pixel.h"
#undef RESOLVE_REAL
#undef RESOLVE_VEC3
#undef RESOLVE_PIXEL
}  // namespace host_resolve

// What turns every pixel's `bins` counts into light, once per image.
host_resolve::ResolveFactors factorsOf(const ResolveParameters& parameters, uint64_t unitsPerBeam, uint32_t bins,
                                       bool hasExactColour) {
  host_resolve::ResolveFactors factors;
  factors.bins = bins;
  factors.exactColour = parameters.useExactColour && hasExactColour;
  factors.irradiancePerCount = parameters.irradiancePerCount;
  const double perBeam = parameters.irradiancePerCount * double(unitsPerBeam);
  factors.xyzPerColourUnit = 683.0 * perBeam / double(device::kColourFixedPointScale);
  const glm::dmat3 m = parameters.xyzToRgb;
  factors.xyzToRgbRow0 = glm::dvec3(m[0][0], m[1][0], m[2][0]);
  factors.xyzToRgbRow1 = glm::dvec3(m[0][1], m[1][1], m[2][1]);
  factors.xyzToRgbRow2 = glm::dvec3(m[0][2], m[1][2], m[2][2]);
  return factors;
}

// Pixel p of `image` from its counters, in double. Bins outside the given
// range hold 0 and would add exactly +0.0, so skipping them changes nothing.
void resolvePixel(const PixelCounters& pixel, size_t p, const host_resolve::ResolveFactors& factors,
                  const ResolveParameters& parameters, uint64_t unitsPerBeam, RenderImage& image,
                  FilmSummary* summary) {
  const host_resolve::PixelResolution sums = host_resolve::resolvePixel(
      {pixel.counts, pixel.colourSums, parameters.binWeights.data() + pixel.firstBin}, factors);
  for (int k = 0; k < 3; ++k) {
    image.xyz[p * 3 + k] = float(sums.xyz[k]);
    image.rgb[p * 3 + k] = float(sums.rgb[k]);
  }
  image.irradiance[p] = float(sums.irradiance);
  if (parameters.beams > 0)
    image.irradianceError[p] = irradianceErrorOfPixel(sums.total, pixel.squaredWeights, parameters.beams,
                                                      unitsPerBeam, parameters.irradiancePerCount, p);
  if (summary) summary->largestCount = std::max(summary->largestCount, sums.largest);
}

}  // namespace

RenderImage resolveOnCpu(const SpectralHistogram& histogram, const ResolveParameters& parameters,
                         FilmSummary* summary) {
  RenderImage image = blankImage(histogram.pixelsX, histogram.pixelsY, parameters.beams > 0);
  const size_t pixels = size_t(histogram.pixelsX) * histogram.pixelsY;
  if (summary) *summary = FilmSummary{histogram.countedBeams, 0};
  const host_resolve::ResolveFactors factors =
      factorsOf(parameters, histogram.unitsPerBeam, histogram.bins, histogram.hasExactColour());
  for (size_t p = 0; p < pixels; ++p) {
    const PixelCounters counters{histogram.counts().data() + p * histogram.bins, 0,
                                 histogram.hasExactColour() ? histogram.colourSums().data() + p * 3 : nullptr,
                                 histogram.isWeighted() ? histogram.squaredWeightSums()[p] : 0};
    resolvePixel(counters, p, factors, parameters, histogram.unitsPerBeam, image, summary);
  }
  return image;
}

RenderImage resolveStoredCountersOnCpu(std::span<const uint64_t> counters, const FilmLayout& film,
                                       const ResolveParameters& parameters, FilmSummary* summary) {
  if (counters.size() != film.storedCounterCount())
    throw std::invalid_argument("resolveStoredCountersOnCpu: the counters do not match the film's layout");
  RenderImage image = blankImage(film.pixelsX, film.pixelsY, parameters.beams > 0);
  const uint32_t stride = film.countersPerPixel();
  const uint32_t colour = device::colourCounterOffset(film.storedBins);
  const uint32_t squared = device::squaredWeightCounterOffset(film.storedBins, film.exactColour);
  const host_resolve::ResolveFactors factors = factorsOf(parameters, film.weightUnits, film.storedBins, film.exactColour);
  for (uint64_t stored = 0; stored < film.storedPixelCount(); ++stored) {
    const uint64_t* src = counters.data() + stored * stride;
    const PixelCounters pixel{src, film.firstStoredBin, film.exactColour ? src + colour : nullptr,
                              film.weighted() ? src[squared] : 0};
    resolvePixel(pixel, film.fullPixelOfStored(stored), factors, parameters, film.weightUnits, image, summary);
  }
  return image;
}

float irradianceErrorOfPixel(uint64_t total, uint64_t squaredWeights, uint64_t beams, uint64_t unitsPerBeam,
                             double irradiancePerCount, size_t pixel) {
  if (beams == 0) return 0.0f;
  const double relativeVariance = pixelRelativeVariance(total, squaredWeights, beams, unitsPerBeam, pixel);
  if (!std::isfinite(relativeVariance)) return 0.0f;  // no counts: no irradiance and no estimate
  return float(std::sqrt(relativeVariance) * (double(total) * irradiancePerCount));
}

std::vector<float> developSpectrum(const SpectralHistogram& histogram, const ResolveParameters& parameters,
                                   double binWidthNm) {
  const double perCount = parameters.irradiancePerCount / binWidthNm;
  std::vector<float> spectrum(histogram.counts().size());
  for (size_t i = 0; i < spectrum.size(); ++i) spectrum[i] = float(double(histogram.counts()[i]) * perCount);
  return spectrum;
}

std::vector<double> binCentresNm(double lambdaMinNm, double lambdaMaxNm, uint32_t bins) {
  std::vector<double> centres(bins);
  const double width = (lambdaMaxNm - lambdaMinNm) / double(bins);
  for (uint32_t b = 0; b < bins; ++b) centres[b] = lambdaMinNm + (double(b) + 0.5) * width;
  return centres;
}

}  // namespace spectrace
