#pragma once
// Spectral power distributions (the seed's SpectralPowerDistribution).
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace spectrace {

// Thrown for invalid spectral input; the message says what is wrong. Callers
// that know the file and field (the scene loader) prefix them.
struct SpdError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A tabulated spectrum (CSV rows, an inline table) has at most this many
// points: far finer than any measured spectrum, and its device table stays
// a few tens of MB (docs/reliability.md "Input limits").
inline constexpr size_t kMaxSpdPoints = 1000000;

// Relative spectral power: a density that is piecewise linear through the
// nodes (lambdaNm[i], value[i]) and zero outside [lambdaNm.front(),
// lambdaNm.back()]. A single node is a Dirac line carrying `value[0]`.
// Units of value are arbitrary (only the shape matters); lengths in nm.
struct Spd {
  std::vector<double> lambdaNm;  // strictly increasing
  std::vector<double> value;     // finite, >= 0, same size as lambdaNm
  // Integral over the light's whole emission in value·nm. Usually the
  // table's own integral, but larger when the table is a window onto a wider
  // emission (a blackbody's tails); `power_w` refers to this whole.
  double fullIntegral = 0.0;

  bool isLine() const { return lambdaNm.size() == 1; }
  // Exact integral of the piecewise-linear density (a line: its value).
  double integral() const;
  // Linear interpolation, zero outside (a line evaluates to 0 everywhere).
  double evaluate(double lambdaNm) const;
  // The part inside [minNm, maxNm], with nodes inserted at the cut points.
  // fullIntegral is kept, so integral()/fullIntegral is the in-range share.
  // May return an Spd with no nodes when nothing lies inside.
  Spd clipped(double minNm, double maxNm) const;
};

// Validates and builds a tabulated SPD. Errors name `what` (e.g. "row 12").
Spd makeTabulatedSpd(std::vector<double> lambdaNm, std::vector<double> value);
// A Dirac line, or a Gaussian of the given FWHM tabulated finely over ±6σ.
Spd makeLineSpd(double centerNm, std::optional<double> fwhmNm = std::nullopt);
// Planck's law tabulated over [minNm, maxNm] finely enough that the
// piecewise-linear table matches it to < 1e-6 relative; fullIntegral is the
// exact total sigma·T^4/pi (in the same units), so the in-range share is right.
Spd makeBlackbodySpd(double kelvin, double minNm, double maxNm);
// Reads "wavelength_nm,value" CSV (a header line is optional; '#' comments
// allowed). With `column`, picks that named column of a multi-column file.
Spd loadCsvSpd(const std::filesystem::path& file, const std::optional<std::string>& column = std::nullopt);
// CIE illuminants from the embedded tables: "A", "D50", "D65", "F1".."F12",
// "F3.1".."F3.15", "LED-B1".."LED-V2". nullopt for an unknown name.
std::optional<Spd> cieIlluminant(std::string_view name);
// Names accepted by cieIlluminant, for error messages.
std::vector<std::string> cieIlluminantNames();

// Planck spectral radiance B(λ, T) in W·sr⁻¹·m⁻²·nm⁻¹ (CODATA 2018 constants).
double planckRadiance(double lambdaNm, double kelvin);

}  // namespace spectrace
