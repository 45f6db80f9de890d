#pragma once
// Histogram -> image on the host (double precision): used by --device cpu
// and as the reference for the resolve shader.
#include <array>
#include <vector>

#include <glm/mat3x3.hpp>

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
};

RenderImage resolveOnCpu(const SpectralHistogram& histogram, const ResolveParameters& parameters);

}  // namespace spectrace
