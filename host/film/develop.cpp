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
// its squared-weight sum; `words` words per counter.
struct PixelCounters {
  const uint64_t* counts;
  uint32_t firstBin;
  const uint64_t* colourSums;
  device::WideCount squaredWeights;
  uint32_t words;
};

device::WideCount counterAt(const uint64_t* words, size_t i, uint32_t wordsPerCounter) {
  return wordsPerCounter == 2 ? device::WideCount{words[2 * i], words[2 * i + 1]} : device::WideCount{words[i], 0};
}

// The shared resolve (shaders/resolve_pixel.h) in double over host counters.
namespace host_resolve {
using namespace device;
using std::max;
using glm::dot;
struct HostPixel {
  const uint64_t* counts;
  const uint64_t* colourSums;
  const std::array<double, 3>* binWeights;  // from the pixel's first bin
  uint32_t words;
};
#define RESOLVE_REAL double
#define RESOLVE_VEC3 glm::dvec3
#define RESOLVE_PIXEL const HostPixel&
inline WideCount resolveBinCount(const HostPixel& pixel, uint bin) { return counterAt(pixel.counts, bin, pixel.words); }
inline WideCount resolveColourSum(const HostPixel& pixel, uint k) { return counterAt(pixel.colourSums, k, pixel.words); }
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
  factors.xyzPerColourUnit = 683.0 * perBeam / double(device::colourUnitsPerCmf(unitsPerBeam != 1));
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
      {pixel.counts, pixel.colourSums, parameters.binWeights.data() + pixel.firstBin, pixel.words}, factors);
  for (int k = 0; k < 3; ++k) {
    image.xyz[p * 3 + k] = float(sums.xyz[k]);
    image.rgb[p * 3 + k] = float(sums.rgb[k]);
  }
  image.irradiance[p] = float(sums.irradiance);
  if (parameters.beams > 0)
    image.irradianceError[p] = irradianceErrorOfPixel(sums.total, pixel.squaredWeights, parameters.beams,
                                                      unitsPerBeam, parameters.irradiancePerCount, p);
  if (summary) addToSummary(*summary, sums.largest, pixel.squaredWeights, unitsPerBeam);
}

}  // namespace

RenderImage resolveOnCpu(const SpectralHistogram& histogram, const ResolveParameters& parameters,
                         FilmSummary* summary) {
  RenderImage image = blankImage(histogram.pixelsX, histogram.pixelsY, parameters.beams > 0);
  const size_t pixels = size_t(histogram.pixelsX) * histogram.pixelsY;
  if (summary) *summary = FilmSummary{histogram.countedBeams, 0};
  const host_resolve::ResolveFactors factors =
      factorsOf(parameters, histogram.unitsPerBeam, histogram.bins, histogram.hasExactColour());
  const uint32_t words = histogram.counterWords();
  for (size_t p = 0; p < pixels; ++p) {
    const PixelCounters counters{
        histogram.counts().data() + p * histogram.bins * words, 0,
        histogram.hasExactColour() ? histogram.colourSums().data() + p * 3 * words : nullptr,
        histogram.isWeighted() ? histogram.counter(device::kFilmChannelSquaredWeight, p) : device::WideCount{0, 0},
        words};
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
  const uint32_t colour = device::colourCounterOffset(film.storedBins, film.weighted());
  const uint32_t squared = device::squaredWeightCounterOffset(film.storedBins, film.exactColour);
  const uint32_t words = device::filmCounterWords(film.channelSet());
  const host_resolve::ResolveFactors factors = factorsOf(parameters, film.weightUnits, film.storedBins, film.exactColour);
  for (uint64_t stored = 0; stored < film.storedPixelCount(); ++stored) {
    const uint64_t* src = counters.data() + stored * stride;
    const PixelCounters pixel{src, film.firstStoredBin, film.exactColour ? src + colour : nullptr,
                              film.weighted() ? counterAt(src + squared, 0, 2) : device::WideCount{0, 0}, words};
    resolvePixel(pixel, film.fullPixelOfStored(stored), factors, parameters, film.weightUnits, image, summary);
  }
  return image;
}

float irradianceErrorOfPixel(device::WideCount total, device::WideCount squaredWeights, uint64_t beams,
                             uint64_t unitsPerBeam, double irradiancePerCount, size_t pixel) {
  if (beams == 0) return 0.0f;
  const double relativeVariance = pixelRelativeVariance(total, squaredWeights, beams, unitsPerBeam, pixel);
  if (!std::isfinite(relativeVariance)) return 0.0f;  // no counts: no irradiance and no estimate
  return float(std::sqrt(relativeVariance) * (realOf(total) * irradiancePerCount));
}

double roundingVarianceShare(const FilmSummary& summary, uint64_t countsBound, bool weighted) {
  if (!weighted || countsBound == 0) return 0.0;
  const double rounding = double(countsBound) * 0x1p-128;
  return rounding / (rounding + summary.squaredWeights);
}

void addToSummary(FilmSummary& summary, device::WideCount largest, device::WideCount squaredWeights,
                  uint64_t unitsPerBeam) {
  summary.largestBeams = std::max(summary.largestBeams, realOf(largest) / double(unitsPerBeam));
  summary.squaredWeights += realOf(squaredWeights) / double(unitsPerBeam);
}

std::vector<float> developSpectrum(const SpectralHistogram& histogram, const ResolveParameters& parameters,
                                   double binWidthNm) {
  const double perCount = parameters.irradiancePerCount / binWidthNm;
  std::vector<float> spectrum(histogram.counts().size() / histogram.counterWords());
  for (size_t i = 0; i < spectrum.size(); ++i)
    spectrum[i] = float(realOf(histogram.counter(device::kFilmChannelBins, i)) * perCount);
  return spectrum;
}

std::vector<double> binCentresNm(double lambdaMinNm, double lambdaMaxNm, uint32_t bins) {
  std::vector<double> centres(bins);
  const double width = (lambdaMaxNm - lambdaMinNm) / double(bins);
  for (uint32_t b = 0; b < bins; ++b) centres[b] = lambdaMinNm + (double(b) + 0.5) * width;
  return centres;
}

}  // namespace spectrace
