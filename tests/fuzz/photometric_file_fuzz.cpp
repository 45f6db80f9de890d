// libFuzzer target: luminaire files, the same bytes read as IES LM-63
// (parseIes) and as EULUMDAT (parseEulumdat). Bad input must end in
// PhotometricFileError, which the scene loader names with its field (exit
// code 2); an accepted table must be what a photometric light relies on:
// C from 0 to 360 and gamma within [0, 180], both strictly ascending, one
// finite non-negative candela value per pair, and finite intensity and flux.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "lights/photometric_file.h"

using namespace spectrace;

namespace {

void checkTable(const PhotometricTable& t) {
  fuzz::require(t.cDegrees.size() >= 2 && t.cDegrees.front() == 0.0 && t.cDegrees.back() == 360.0,
                "C does not run from 0 to 360");
  fuzz::require(!t.gammaDegrees.empty() && t.gammaDegrees.front() >= 0.0 && t.gammaDegrees.back() <= 180.0,
                "gamma leaves [0, 180]");
  for (size_t i = 1; i < t.cDegrees.size(); ++i) fuzz::require(t.cDegrees[i] > t.cDegrees[i - 1], "C not ascending");
  for (size_t i = 1; i < t.gammaDegrees.size(); ++i)
    fuzz::require(t.gammaDegrees[i] > t.gammaDegrees[i - 1], "gamma not ascending");
  fuzz::require(t.candela.size() == t.cDegrees.size() * t.gammaDegrees.size(), "candela count differs from the angles'");
  for (double v : t.candela) {
    fuzz::requireFinite(v, "a candela value");
    fuzz::require(v >= 0.0, "a negative candela value was accepted");
  }
  if (t.ratedLumens) {
    fuzz::requireFinite(*t.ratedLumens, "the rated lumens");
    fuzz::require(*t.ratedLumens > 0.0, "rated lumens not positive");
  }
  if (t.gammaDegrees.size() >= 2) {
    const double flux = t.tableLumens();
    fuzz::requireFinite(flux, "the table's flux");
    fuzz::require(flux >= 0.0, "a negative flux");
  }
  for (double c : {0.0, 45.5, 181.0, 359.9})
    for (double g : {0.0, 30.0, 90.0, 179.0}) fuzz::requireFinite(t.intensity(c, g), "an interpolated intensity");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    checkTable(parseIes(text, "fuzz.ies"));
  } catch (const PhotometricFileError&) {
  }
  try {
    checkTable(parseEulumdat(text, "fuzz.ldt"));
  } catch (const PhotometricFileError&) {
  }
  return 0;
}
