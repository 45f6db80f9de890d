#pragma once
// Sampling tables built in double precision on the host (the seed's
// getNextLambda(), done exactly). Discrete choices use integer CDFs over a
// 64-bit uniform: choice j has probability exactly width_j / 2^64, a zero
// weight gets width 0 (never drawn) and a positive weight at least 1 (always
// drawable). Within an interval, the density is linear between the SPD's
// nodes and is sampled in closed form (shaders/beam_math.h).
#include <cstdint>
#include <span>
#include <vector>

#include "device_shared.h"
#include "spectrum/spd.h"

namespace spectrace {

// Lower ends of the integer CDF of `weights` (finite, >= 0, at least one
// > 0, and the last one > 0 so every low end fits in 64 bits). Widths sum to
// exactly 2^64; each positive width is the weight's share of 2^64, rounded
// down (at least 1), with the rounding remainder given to the largest.
std::vector<uint64_t> quantizeCdf(std::span<const double> weights);

// Exact probability of choice j of an integer CDF (double-rounded only at
// the end: (width_j) * 2^-64).
double cdfProbability(std::span<const uint64_t> lows, size_t j);

struct SpectralTable {
  std::vector<device::SpectralInterval> intervals;  // cdfLow relative to this light
  double integral = 0.0;                            // of the sampled SPD, value·nm
};

// Intervals of a (clipped) SPD, trimmed of zero-power intervals at both ends.
// A Dirac line becomes one interval of width 0. Throws SpdError when the SPD
// has no power.
SpectralTable buildSpectralTable(const Spd& spd);

// The probability that the sampler draws a wavelength in [a, b] (a < b
// inside one interval or spanning several), integrated exactly from the
// very tables the shader uses, as the reference for chi-square tests.
double tableProbability(const SpectralTable& table, double aNm, double bNm);

}  // namespace spectrace
