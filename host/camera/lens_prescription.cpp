#include "camera/lens_prescription.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "spectrum/glass.h"

namespace spectrace {

double LensMedium::indexAt(double lambdaNm) const { return isAir() ? 1.0 : sellmeierIndex(b, cUm2, lambdaNm); }

// r^2 / (R (1 + sqrt(1 - r^2 / R^2))): R - sqrt(R^2 - r^2) for R > 0 and its
// mirror for R < 0, without the cancellation near the axis.
double LensSurface::sagAt(double r) const {
  if (radiusM == 0.0) return 0.0;
  const double x = r / radiusM;
  return r * r / (radiusM * (1.0 + std::sqrt(std::max(1.0 - x * x, 0.0))));
}

std::vector<double> LensPrescription::vertexZ() const {
  std::vector<double> z(surfaces.size(), 0.0);
  double at = 0.0;
  for (size_t i = surfaces.size(); i-- > 0;) {
    at += surfaces[i].thicknessM;
    z[i] = at;
  }
  return z;
}

double LensPrescription::frontZ() const {
  const LensSurface& first = surfaces.front();
  return vertexZ().front() - std::min(0.0, first.sagAt(first.semiApertureM));
}

double LensPrescription::widestSemiApertureM() const {
  double widest = 0.0;
  for (const LensSurface& s : surfaces) widest = std::max(widest, s.semiApertureM);
  return widest;
}

bool LensPrescription::disperses() const {
  return std::any_of(surfaces.begin(), surfaces.end(), [](const LensSurface& s) { return s.medium.disperses(); });
}

ParaxialMatrix paraxialMatrix(const LensPrescription& lens, double lambdaNm) {
  return lens.surfaces.empty() ? ParaxialMatrix{} : paraxialMatrixThrough(lens, lambdaNm, lens.surfaces.size() - 1);
}

ParaxialMatrix paraxialMatrixThrough(const LensPrescription& lens, double lambdaNm, size_t last) {
  ParaxialMatrix m;
  double before = 1.0;
  for (size_t i = 0; i <= last && i < lens.surfaces.size(); ++i) {
    const LensSurface& s = lens.surfaces[i];
    const double after = s.medium.indexAt(lambdaNm);
    const double power = s.radiusM == 0.0 ? 0.0 : (after - before) / s.radiusM;
    // [1 0; -P 1] * m
    m = {m.a, m.b, m.c - power * m.a, m.d - power * m.b};
    if (i < last && i + 1 < lens.surfaces.size()) {
      const double reduced = s.thicknessM / after;  // [1 t/n; 0 1] * m
      m = {m.a + reduced * m.c, m.b + reduced * m.d, m.c, m.d};
    }
    before = after;
  }
  return m;
}

// A ray parallel to the axis at height y leaves the last surface at height
// a y with slope c y (in air), so it crosses the axis -a / c behind the last
// vertex, the back focal point, and f = -1 / c; the back principal plane is
// f before that, (1 - a) / c. The front ones mirror it: the ray from the
// front focal point, -d / c before the first vertex, leaves parallel, and
// the front principal plane lies f behind that point, (d - 1) / c.
std::optional<ParaxialCardinal> paraxialCardinal(const LensPrescription& lens, double lambdaNm) {
  const ParaxialMatrix m = paraxialMatrix(lens, lambdaNm);
  if (!(m.c != 0.0) || !std::isfinite(m.c)) return std::nullopt;
  return ParaxialCardinal{-1.0 / m.c, (m.d - 1.0) / m.c, (1.0 - m.a) / m.c};
}

// With the sensor t behind the last vertex and the object D before the
// sensor, the object lies s_o before the front principal plane and the
// image s_i behind the back one, s_o + s_i = D - (the planes' separation)
// = S, and 1/s_o + 1/s_i = 1/f: s_i^2 - S s_i + f S = 0, whose smaller root
// (s_i -> f as D grows) is taken.
std::optional<double> focusedBackThicknessM(const LensPrescription& lens, double focusDistanceM, double lambdaNm) {
  const auto cardinal = paraxialCardinal(lens, lambdaNm);
  if (!cardinal || !(cardinal->focalLengthM > 0.0)) return std::nullopt;
  double body = 0.0;  // first vertex to last
  for (size_t i = 0; i + 1 < lens.surfaces.size(); ++i) body += lens.surfaces[i].thicknessM;
  const double separation = body + cardinal->backPrincipalM - cardinal->frontPrincipalM;
  const double sum = focusDistanceM - separation;
  const double f = cardinal->focalLengthM;
  const double discriminant = sum * sum - 4.0 * f * sum;
  if (!(sum > 0.0) || !(discriminant >= 0.0)) return std::nullopt;
  const double image = 0.5 * (sum - std::sqrt(discriminant));
  const double back = image + cardinal->backPrincipalM;
  if (!(back > 0.0) || !std::isfinite(back)) return std::nullopt;
  return back;
}

namespace {

// The stop's index and the stop height per entrance height, |a|.
std::optional<std::pair<size_t, double>> stopAndHeightRatio(const LensPrescription& lens, double lambdaNm) {
  std::optional<size_t> stop;
  for (size_t i = 0; i < lens.surfaces.size(); ++i)
    if (lens.surfaces[i].stop) {
      if (stop) return std::nullopt;
      stop = i;
    }
  if (!stop) return std::nullopt;
  const double ratio = std::abs(paraxialMatrixThrough(lens, lambdaNm, *stop).a);
  if (!(ratio > 0.0) || !std::isfinite(ratio)) return std::nullopt;
  return std::pair{*stop, ratio};
}

}  // namespace

std::optional<double> fNumber(const LensPrescription& lens, double lambdaNm) {
  const auto stop = stopAndHeightRatio(lens, lambdaNm);
  const auto cardinal = paraxialCardinal(lens, lambdaNm);
  if (!stop || !cardinal || !(cardinal->focalLengthM > 0.0)) return std::nullopt;
  return cardinal->focalLengthM * stop->second / (2.0 * lens.surfaces[stop->first].semiApertureM);
}

}  // namespace spectrace
