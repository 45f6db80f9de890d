#pragma once
// The glass catalogue: three-term Sellmeier coefficients of a few optical
// glasses (data/glass/sellmeier.csv, compiled in; sources in its README).
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace spectrace {

// n^2(lambda) = 1 + sum_i b[i] lambda^2 / (lambda^2 - cUm2[i]), lambda in um.
struct SellmeierGlass {
  std::string name;
  std::array<double, 3> b;
  std::array<double, 3> cUm2;
};

// The catalogue glass of exactly this name (case included); nullptr when
// there is none.
const SellmeierGlass* glassNamed(std::string_view name);

// The catalogue's glass names, in file order.
std::vector<std::string> glassNames();

// The Sellmeier index at lambdaNm (vacuum wavelength in nm). NaN where the
// formula has no real index (n^2 <= 0) or at a pole; callers validate, since
// only they know which range they need.
double sellmeierIndex(const std::array<double, 3>& b, const std::array<double, 3>& cUm2, double lambdaNm);

// Why a Sellmeier index (every b, c >= 0) labelled `label` gives no usable
// index over [minNm, maxNm]: a pole inside the range, or n not finite and
// >= 1 there; "" when it does. Dielectric materials and lens media share it.
std::string sellmeierRangeProblem(const std::array<double, 3>& b, const std::array<double, 3>& cUm2,
                                  const std::string& label, double minNm, double maxNm);

// The Fraunhofer lines the Abbe number is defined on (ISO 7944): helium d,
// hydrogen F and C, vacuum wavelengths in nm.
inline constexpr double kLineDNm = 587.5618;
inline constexpr double kLineFNm = 486.1327;
inline constexpr double kLineCNm = 656.2725;

// A model glass of index nd at the d line and Abbe number vd = (nd - 1) /
// (nF - nC): the one-term Sellmeier form n^2 = 1 + b l^2 / (l^2 - c) (W.
// Sellmeier, Ann. Phys. 219, 272 (1871); a single-oscillator model, as in
// S. H. Wemple and M. DiDomenico, Phys. Rev. B 3, 1338 (1971)), with b and
// c fitted so that it has exactly that nd and vd. It keeps the catalogue's
// formula (the kernel evaluates no other) and disperses normally: n falls
// with the wavelength, steeply towards its one pole at sqrt(c) in the UV.
// nullopt unless nd > 1 and vd > 0 are finite; nd = 1 is air.
std::optional<SellmeierGlass> modelGlass(double nd, double vd);

}  // namespace spectrace
