#pragma once
// The glass catalogue: three-term Sellmeier coefficients of a few optical
// glasses (data/glass/sellmeier.csv, compiled in; sources in its README).
#include <array>
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

}  // namespace spectrace
