#pragma once
// Colour science (the seed's Color::SPDtoRGB): CIE observers, XYZ, sRGB.
#include <array>
#include <span>
#include <string_view>
#include <vector>

#include <glm/mat3x3.hpp>

#include "device_shared.h"
#include "spectrum/spd.h"

namespace spectrace {

// A colour-matching-function table, 1 nm steps as published, piecewise
// linear between nodes and zero outside.
struct Observer {
  std::string_view name;
  std::vector<double> lambdaNm;
  std::vector<double> xbar, ybar, zbar;
};
const Observer& cie1931Observer();  // "CIE1931_2" (default)
const Observer& cie1964Observer();  // "CIE1964_10"
// By name ("CIE1931_2" or "CIE1964_10"); throws std::invalid_argument otherwise.
const Observer& observerByName(std::string_view name);
// (x̄, ȳ, z̄) at a wavelength: linear interpolation, zero outside the table.
std::array<double, 3> cmfAt(const Observer& obs, double lambdaNm);

constexpr double kLumensPerWatt = 683.0;

// Bin-averaged CMFs for `bins` equal bins over [minNm, maxNm]:
// w[b] = (1/Δλ) ∫_bin cmf(λ) dλ, integrated exactly (the CMF is piecewise
// linear) in double. X = 683 · Σ_b E_b · w[b].x for per-bin irradiance E_b.
std::vector<std::array<double, 3>> binAveragedCmf(const Observer& obs, double minNm, double maxNm, int bins);

// The mean CMF of the wavelengths a light's spectral table draws, given that
// they fall in bin b of `bins` equal bins over [minNm, maxNm]:
// E[cmf(λ) | bin b] under the sampled density (each interval's exact
// probability, linear inside it; a line at its wavelength), integrated
// exactly in double. Bins the table never reaches get bin-averaged CMFs.
// X = 683 · Σ_b E_b · w[b].x then has the expectation of per-beam exact
// colour for beams of this table (the colour-from-bins shortcut).
std::vector<std::array<double, 3>> sampledBinCmfMeans(std::span<const device::SpectralInterval> intervals,
                                                      const Observer& obs, double minNm, double maxNm, int bins);

// Tristimulus values of an SPD by exact integration of the product of the
// two piecewise-linear functions (a line: the CMF at its wavelength), in
// (value units)·nm. No 683 factor.
std::array<double, 3> spdToXyz(const Spd& spd, const Observer& obs);
// Plain summation Σ S(λ_i)·cmf(λ_i) over the CMF's 1 nm nodes, as CIE 015
// tabulates chromaticities.
std::array<double, 3> spdToXyzSummed(const Spd& spd, const Observer& obs);

std::array<double, 2> chromaticity(const std::array<double, 3>& xyz);

// XYZ -> linear sRGB (Rec. 709 primaries, D65 white (0.3127, 0.3290)),
// derived from the primaries in double precision. glm is column-major:
// rgb = M * xyz.
glm::dmat3 xyzToLinearSrgb();
// Derivation for any primaries and white point (xy chromaticities).
glm::dmat3 xyzToRgbFromPrimaries(std::array<double, 2> r, std::array<double, 2> g,
                                 std::array<double, 2> b, std::array<double, 2> white);

}  // namespace spectrace
