#pragma once
// Error of a render against a reference image, for the benchmark's run time
// versus error curves: relative MSE (and its RMSE, bias), CIEDE2000 colour
// error, chromaticity error of the whole image, and how well the render's own
// count statistics predict its error ("honesty").
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "film/pixel_variance.h"
#include "film/spectral_histogram.h"
#include "io/image.h"

namespace spectrace {

// What a render is compared against: exact per-pixel irradiance (W/m^2) and
// XYZ (Y in lux), row-major like RenderImage, and which pixels count
// (valid[i] != 0).
struct ReferenceImage {
  int width = 0, height = 0;
  std::vector<double> irradiance;  // 1 per pixel
  std::vector<double> xyz;         // 3 per pixel
  std::vector<uint8_t> valid;      // 1 per pixel
};

// Every mean is over a stated pixel set; a metric whose set is empty (or
// whose inputs are missing) is NaN.
struct ErrorMetrics {
  // Valid pixels with reference irradiance > 0: the set for relRmse, relMse
  // and bias. (A valid pixel with zero reference irradiance has no relative
  // error; it is left out.)
  size_t pixels = 0;
  // Relative errors r = (E - Eref) / Eref of the irradiance over `pixels`.
  // relMse = mean(r^2): the pbrt/Mitsuba relative MSE, (E - Eref)^2 / Eref^2,
  // but WITHOUT their epsilon in the denominator (they add ~1e-2 to Eref^2 to
  // survive black pixels): pixels with Eref = 0 are excluded instead, which
  // keeps relMse independent of the image's absolute scale.
  double relRmse = 0.0;  // sqrt(relMse)
  double relMse = 0.0;
  double bias = 0.0;     // mean(r): mean signed relative error
  // CIEDE2000 between the render's and the reference's pixel colours over
  // valid pixels with reference Y > 0 (deltaEPixels of them). Both XYZ are
  // taken to CIELAB against one white for the whole image: D65 chromaticity
  // (x, y) = (0.3127, 0.3290), the sRGB white used by colour.h, at
  // Y_white = the largest reference Y over valid pixels. So the brightest
  // pixel of the reference is L* = 100 and ΔE measures colour error at the
  // image's own exposure (a dim pixel's error counts as a dark colour's).
  size_t deltaEPixels = 0;
  double deltaE2000Mean = 0.0;
  double deltaE2000P99 = 0.0;  // nearest-rank 99th percentile
  // Euclidean distance between the (x, y) chromaticity of the render's XYZ
  // summed over valid pixels and that of the reference's (the colour of the
  // image as a whole).
  double meanChromaticityError = 0.0;
  // Relative error of the whole image's Y (sum over valid pixels), and the
  // estimated relative standard error of the whole image's irradiance,
  // sqrt(sum v_i Eref_i^2) / sum Eref_i over pixels with an estimate (NaN
  // without). Y's own noise is larger by sqrt(E[ybar^2] / E[ybar]^2) over
  // the spectrum, at most ~2 for broad spectra.
  double luminanceError = 0.0;
  double estimatedTotalRelError = 0.0;
  // Honesty of the render's own error estimate, over the pixels of `pixels`
  // that have an estimate (finite estimated relative variance); the others
  // (e.g. zero counts) are skipped and counted in pixelsWithoutEstimate.
  // estimatedRelRmse = sqrt(mean(estimated relative variance)) and honesty =
  // (relRmse over the same pixels) / estimatedRelRmse, ~1 when the render's
  // error is the statistical noise its counts predict, > 1 when there is
  // more (bias, wrong estimate). Both NaN if no estimate is given.
  size_t pixelsWithoutEstimate = 0;
  double estimatedRelRmse = 0.0;
  double honesty = 0.0;
};

// estimatedRelativeVariance (the render's own per-pixel error estimate) is
// film's: film/pixel_variance.h.

// `estimatedRelVariance`: one per pixel (NaN where unknown), or empty for none.
// Throws std::invalid_argument if the images' shapes or buffer sizes differ.
ErrorMetrics computeErrorMetrics(const RenderImage& render, const ReferenceImage& reference,
                                 const std::vector<double>& estimatedRelVariance);

// Figure of merit: 1 / (relMSE * seconds), higher is better. +infinity for
// relMse == 0; throws std::invalid_argument for relMse < 0, seconds <= 0 or
// non-finite / NaN inputs.
double figureOfMerit(double relMse, double seconds);

// CIEDE2000 (Sharma, Wu, Dalal 2005, kL = kC = kH = 1) between two CIELAB
// colours (L*, a*, b*). Symmetric.
double ciede2000(std::array<double, 3> lab1, std::array<double, 3> lab2);
// CIE 1976 L*a*b* of `xyz` relative to the white `white` (CIE 015 formulae,
// exact constants ε = 216/24389, κ = 24389/27; negative ratios follow the
// linear branch).
std::array<double, 3> xyzToLab(std::array<double, 3> xyz, std::array<double, 3> white);

}  // namespace spectrace
