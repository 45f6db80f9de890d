#pragma once
// Luminaire photometry files: IES LM-63 (1986, 1991, 1995, 2002 and 2019
// layouts; Type C photometry, TILT=NONE) and EULUMDAT, read into one
// goniometric table of candela over the C and gamma angles, every symmetry
// of the file unfolded to C from 0 to 360 degrees: what a photometric
// light needs of its file. Intensity between the table's angles is
// bilinear in C and gamma, as LM-63 readers conventionally take it; the
// table's flux integrates that interpolation exactly.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace spectrace {

// A file that cannot be read as photometry: the message names the file,
// the line and what is wrong.
struct PhotometricFileError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// C = 0 is the luminaire's C = 0 half-plane, C grows counter-clockwise seen
// from above (towards nadir), gamma = 0 is nadir and 180 zenith (CIE 121,
// Type C).
struct PhotometricTable {
  std::vector<double> cDegrees;      // ascending, from 0 to 360
  std::vector<double> gammaDegrees;  // ascending, within [0, 180]; no light outside
  // candela[c * gammaDegrees.size() + g]: the file's values times its
  // candela multiplier and ballast factors.
  std::vector<double> candela;
  // Lamps times rated lumens per lamp; absent for absolute photometry (the
  // file's -1 lumens), where the table's own flux is the luminaire's.
  std::optional<double> ratedLumens;
  double inputWatts = 0.0;

  double at(size_t c, size_t g) const { return candela[c * gammaDegrees.size() + g]; }
  // Bilinear in C and gamma (degrees); C taken modulo 360, 0 outside the
  // gamma range.
  double intensity(double cDeg, double gammaDeg) const;
  // The flux of the bilinear table in lumens over the patch between C
  // entries c, c + 1 and gamma entries g, g + 1: the integral of I sin(gamma)
  // in closed form. tableLumens sums every patch.
  double patchLumens(size_t c, size_t g) const;
  double tableLumens() const;
};

// `name` is what messages call the text (its file's path).
PhotometricTable parseIes(std::string_view text, const std::string& name);
PhotometricTable readIesFile(const std::filesystem::path& path);
// EULUMDAT (.ldt): every symmetry indicator (0-4). Intensities are given
// per 1000 lm of the lamps; the first set of lamps' flux (and the file's
// conversion factor) makes them candela, and is the rated flux.
PhotometricTable parseEulumdat(std::string_view text, const std::string& name);
PhotometricTable readEulumdatFile(const std::filesystem::path& path);
// By the extension: .ies or .ldt (any case).
PhotometricTable readPhotometricFile(const std::filesystem::path& path);

}  // namespace spectrace
