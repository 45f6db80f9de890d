#pragma once
// Histogram -> image on the host (double precision): used by --device cpu
// and as the reference for the resolve shader.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat3x3.hpp>

#include "film/film_layout.h"
#include "film/spectral_histogram.h"
#include "io/image.h"

namespace spectrace {

// What turns counts into colour: the bin weights are 683 x the bin-averaged
// CMFs (lm/W), the matrix maps XYZ to linear sRGB.
struct ResolveParameters {
  std::vector<std::array<double, 3>> binWeights;
  glm::dmat3 xyzToRgb{1.0};
  // W/m^2 per count (per bin counter unit). A full-weight beam adds
  // unitsPerBeam counts, and its colour sums are in CMF x weight ratio, so
  // they scale with irradiancePerCount x unitsPerBeam.
  double irradiancePerCount = 0.0;
  // Take XYZ from the per-beam colour sums when the histogram has them
  // (exact whatever the bin count), else from the bin-averaged CMFs.
  bool useExactColour = true;
  // The beams the film holds; with beams > 0 develop also writes each
  // pixel's error estimate (error.E, irradianceErrorOfPixel).
  uint64_t beams = 0;
};

// What develop reports about the film besides the image, from the pixels'
// exact sums: no download of the film is needed for it.
struct FilmSummary {
  uint64_t countedBeams = 0;   // beams counted (each added to one bin)
  double largestBeams = 0.0;   // the largest pixel-bin counter, in full-weight beams
  double squaredWeights = 0.0; // the sum of every count's squared weight ratio (weighted films)
};

// Histogram -> image; `summary`, when given, gets the largest count and
// the histogram's counted beams.
RenderImage resolveOnCpu(const SpectralHistogram& histogram, const ResolveParameters& parameters,
                         FilmSummary* summary = nullptr);
// The same from the device layout of the film's stored pixels and bins
// (FilmLayout: the CPU reference's counters), without building a histogram:
// bit-identical to resolveOnCpu of the unpacked film. The summary's counted
// beams are left to the caller.
RenderImage resolveStoredCountersOnCpu(std::span<const uint64_t> counters, const FilmLayout& film,
                                       const ResolveParameters& parameters, FilmSummary* summary = nullptr);

// One pixel's estimated standard error of its irradiance in W/m^2:
// sqrt(pixelRelativeVariance) x irradiance, the irradiance in double from
// the pixel's total count; 0 for an empty pixel (no estimate) and for
// beams == 0.
float irradianceErrorOfPixel(device::WideCount total, device::WideCount squaredWeights, uint64_t beams,
                             uint64_t unitsPerBeam, double irradiancePerCount, size_t pixel);
// The largest share of the film's variance its fixed point can add. A plain
// film counts hits exactly (0). A weighted film's count is exact when its
// weight ratio is at least 2^-39, else rounded stochastically (unbiased),
// adding at most 1/4 unit^2 = 2^-128 beams^2 of variance, against the
// count's own r^2 (device_shared.h, kWeightUnitsFractional). With at most
// `countsBound` counts: R / (R + S), R = countsBound x 2^-128, S = the
// summary's sum of squared weights.
double roundingVarianceShare(const FilmSummary& summary, uint64_t countsBound, bool weighted);
// Adds one pixel's exact sums to the summary.
void addToSummary(FilmSummary& summary, device::WideCount largest, device::WideCount squaredWeights,
                  uint64_t unitsPerBeam);

// Spectral irradiance in W m^-2 nm^-1 of every pixel and bin of the
// histogram, [pixel][bin] like its counts: count x irradiancePerCount /
// binWidthNm, in double then rounded to float. So a pixel's bins times the
// bin width sum to its irradiance. Bins the device did not store are 0.
std::vector<float> developSpectrum(const SpectralHistogram& histogram, const ResolveParameters& parameters,
                                   double binWidthNm);
// The centre of each bin in nm (bins of equal width from lambdaMinNm).
std::vector<double> binCentresNm(double lambdaMinNm, double lambdaMaxNm, uint32_t bins);

}  // namespace spectrace
