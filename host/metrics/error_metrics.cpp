#include "metrics/error_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace spectrace {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double degrees(double radians) { return radians * (180.0 / std::numbers::pi); }
double radians(double degrees) { return degrees * (std::numbers::pi / 180.0); }

// Hue angle in degrees, [0, 360); 0 for a = b = 0 (Sharma eq. 4 convention).
double hueDegrees(double b, double a) {
  if (a == 0.0 && b == 0.0) return 0.0;
  double h = degrees(std::atan2(b, a));
  if (h < 0.0) h += 360.0;
  if (h >= 360.0) h -= 360.0;
  return h;
}

// Chromaticity (x, y); NaN if the sum X + Y + Z is not positive.
std::array<double, 2> xyOf(const std::array<double, 3>& xyz) {
  const double s = xyz[0] + xyz[1] + xyz[2];
  if (!(s > 0.0)) return {kNaN, kNaN};
  return {xyz[0] / s, xyz[1] / s};
}

}  // namespace

ErrorMetrics computeErrorMetrics(const RenderImage& render, const ReferenceImage& reference,
                                 const std::vector<double>& estimatedRelVariance) {
  if (render.width != reference.width || render.height != reference.height || render.width < 0 ||
      render.height < 0)
    throw std::invalid_argument("computeErrorMetrics: render and reference differ in size");
  const size_t n = size_t(render.width) * size_t(render.height);
  if (render.irradiance.size() != n || render.xyz.size() != 3 * n)
    throw std::invalid_argument("computeErrorMetrics: render buffers do not match its size");
  if (reference.irradiance.size() != n || reference.xyz.size() != 3 * n || reference.valid.size() != n)
    throw std::invalid_argument("computeErrorMetrics: reference buffers do not match its size");
  const bool haveEstimate = !estimatedRelVariance.empty();
  if (haveEstimate && estimatedRelVariance.size() != n)
    throw std::invalid_argument("computeErrorMetrics: estimated variance has " +
                                std::to_string(estimatedRelVariance.size()) + " entries for " +
                                std::to_string(n) + " pixels");

  ErrorMetrics m;
  // Relative irradiance error, and the honesty sums over pixels with an estimate.
  double sumR = 0.0, sumR2 = 0.0, sumR2Est = 0.0, sumVar = 0.0;
  double sumEref = 0.0, sumVarE = 0.0;  // for the whole image's estimated relative error
  size_t estimated = 0;
  // Whole-image XYZ sums (valid pixels) and the white for CIELAB.
  std::array<double, 3> sumRender{0, 0, 0}, sumRef{0, 0, 0};
  double maxRefY = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (!reference.valid[i]) continue;
    for (int k = 0; k < 3; ++k) {
      sumRender[k] += double(render.xyz[3 * i + k]);
      sumRef[k] += reference.xyz[3 * i + k];
    }
    maxRefY = std::max(maxRefY, reference.xyz[3 * i + 1]);
    const double eref = reference.irradiance[i];
    if (!(eref > 0.0)) continue;
    const double r = (double(render.irradiance[i]) - eref) / eref;
    ++m.pixels;
    sumR += r;
    sumR2 += r * r;
    if (haveEstimate) {
      const double v = estimatedRelVariance[i];
      sumEref += eref;
      if (std::isfinite(v)) {
        ++estimated;
        sumR2Est += r * r;
        sumVar += v;
        sumVarE += v * eref * eref;
      } else {
        ++m.pixelsWithoutEstimate;
      }
    }
  }
  if (m.pixels > 0) {
    m.relMse = sumR2 / double(m.pixels);
    m.relRmse = std::sqrt(m.relMse);
    m.bias = sumR / double(m.pixels);
  } else {
    m.relMse = m.relRmse = m.bias = kNaN;
  }
  m.luminanceError = sumRef[1] > 0.0 ? (sumRender[1] - sumRef[1]) / sumRef[1] : kNaN;
  m.estimatedTotalRelError = estimated > 0 && sumEref > 0.0 ? std::sqrt(sumVarE) / sumEref : kNaN;
  if (estimated > 0) {
    m.estimatedRelRmse = std::sqrt(sumVar / double(estimated));
    m.honesty = std::sqrt(sumR2Est / double(estimated)) / m.estimatedRelRmse;
  } else {
    m.estimatedRelRmse = m.honesty = kNaN;
  }

  // CIEDE2000 per pixel against one white: D65 chromaticity at the brightest
  // reference luminance (see the header).
  std::vector<double> deltaE;
  if (maxRefY > 0.0) {
    const double wx = 0.3127, wy = 0.3290;
    const std::array<double, 3> white{maxRefY * wx / wy, maxRefY, maxRefY * (1.0 - wx - wy) / wy};
    deltaE.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      if (!reference.valid[i] || !(reference.xyz[3 * i + 1] > 0.0)) continue;
      const std::array<double, 3> xr{double(render.xyz[3 * i]), double(render.xyz[3 * i + 1]),
                                     double(render.xyz[3 * i + 2])};
      const std::array<double, 3> xf{reference.xyz[3 * i], reference.xyz[3 * i + 1], reference.xyz[3 * i + 2]};
      deltaE.push_back(ciede2000(xyzToLab(xr, white), xyzToLab(xf, white)));
    }
  }
  m.deltaEPixels = deltaE.size();
  if (!deltaE.empty()) {
    double s = 0.0;
    for (double d : deltaE) s += d;
    m.deltaE2000Mean = s / double(deltaE.size());
    // Nearest rank: the ceil(0.99 n)-th smallest value.
    const size_t rank = size_t(std::ceil(0.99 * double(deltaE.size())));
    const size_t k = std::max<size_t>(rank, 1) - 1;
    std::nth_element(deltaE.begin(), deltaE.begin() + std::ptrdiff_t(k), deltaE.end());
    m.deltaE2000P99 = deltaE[k];
  } else {
    m.deltaE2000Mean = m.deltaE2000P99 = kNaN;
  }

  const auto xyR = xyOf(sumRender), xyF = xyOf(sumRef);
  m.meanChromaticityError = std::hypot(xyR[0] - xyF[0], xyR[1] - xyF[1]);  // NaN propagates
  return m;
}

double figureOfMerit(double relMse, double seconds) {
  if (!(relMse >= 0.0) || !std::isfinite(relMse) || !(seconds > 0.0) || !std::isfinite(seconds))
    throw std::invalid_argument("figureOfMerit needs a finite relMse >= 0 and finite seconds > 0");
  if (relMse == 0.0) return std::numeric_limits<double>::infinity();
  return 1.0 / (relMse * seconds);
}

std::array<double, 3> xyzToLab(std::array<double, 3> xyz, std::array<double, 3> white) {
  constexpr double eps = 216.0 / 24389.0;  // (6/29)^3
  constexpr double kappa = 24389.0 / 27.0;  // (29/3)^3
  const auto f = [&](double t) { return t > eps ? std::cbrt(t) : (kappa * t + 16.0) / 116.0; };
  const double fx = f(xyz[0] / white[0]), fy = f(xyz[1] / white[1]), fz = f(xyz[2] / white[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double ciede2000(std::array<double, 3> lab1, std::array<double, 3> lab2) {
  const double L1 = lab1[0], a1 = lab1[1], b1 = lab1[2];
  const double L2 = lab2[0], a2 = lab2[1], b2 = lab2[2];
  constexpr double p25_7 = 6103515625.0;  // 25^7
  // (2)-(7): a' with the G correction, C', h'.
  const double C1 = std::hypot(a1, b1), C2 = std::hypot(a2, b2);
  const double Cbar7 = std::pow(0.5 * (C1 + C2), 7);
  const double G = 0.5 * (1.0 - std::sqrt(Cbar7 / (Cbar7 + p25_7)));
  const double a1p = (1.0 + G) * a1, a2p = (1.0 + G) * a2;
  const double C1p = std::hypot(a1p, b1), C2p = std::hypot(a2p, b2);
  const double h1p = hueDegrees(b1, a1p), h2p = hueDegrees(b2, a2p);
  const bool achromatic = C1p * C2p == 0.0;
  // (8)-(11): differences.
  const double dLp = L2 - L1;
  const double dCp = C2p - C1p;
  double dhp = 0.0;
  if (!achromatic) {
    dhp = h2p - h1p;
    if (dhp > 180.0) dhp -= 360.0;
    else if (dhp < -180.0) dhp += 360.0;
  }
  const double dHp = 2.0 * std::sqrt(C1p * C2p) * std::sin(radians(dhp / 2.0));
  // (12)-(22): means and weights.
  const double Lbarp = 0.5 * (L1 + L2);
  const double Cbarp = 0.5 * (C1p + C2p);
  double hbarp;
  if (achromatic) hbarp = h1p + h2p;
  else if (std::abs(h1p - h2p) <= 180.0) hbarp = 0.5 * (h1p + h2p);
  else if (h1p + h2p < 360.0) hbarp = 0.5 * (h1p + h2p + 360.0);
  else hbarp = 0.5 * (h1p + h2p - 360.0);
  const double T = 1.0 - 0.17 * std::cos(radians(hbarp - 30.0)) + 0.24 * std::cos(radians(2.0 * hbarp)) +
                   0.32 * std::cos(radians(3.0 * hbarp + 6.0)) - 0.20 * std::cos(radians(4.0 * hbarp - 63.0));
  const double dTheta = 30.0 * std::exp(-std::pow((hbarp - 275.0) / 25.0, 2));
  const double Cbarp7 = std::pow(Cbarp, 7);
  const double RC = 2.0 * std::sqrt(Cbarp7 / (Cbarp7 + p25_7));
  const double l50 = (Lbarp - 50.0) * (Lbarp - 50.0);
  const double SL = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double SC = 1.0 + 0.045 * Cbarp;
  const double SH = 1.0 + 0.015 * Cbarp * T;
  const double RT = -std::sin(radians(2.0 * dTheta)) * RC;
  const double tl = dLp / SL, tc = dCp / SC, th = dHp / SH;
  return std::sqrt(std::max(0.0, tl * tl + tc * tc + th * th + RT * tc * th));
}

}  // namespace spectrace
