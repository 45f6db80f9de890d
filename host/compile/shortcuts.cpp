#include "compile/shortcuts.h"

namespace spectrace {

const char* shortcutName(Shortcut shortcut) {
  switch (shortcut) {
    case Shortcut::SkipUnreachableLights: return "skip unreachable lights";
    case Shortcut::AimAtCamera: return "aim at the camera";
    case Shortcut::TrimSpectrum: return "trim the spectrum";
    case Shortcut::TrimPixels: return "trim the sensor";
    case Shortcut::ColourFromBins: return "colour from bins";
  }
  return "?";
}

// Every precondition today is the same: a beam travels in a straight line
// from its light to the sensor, so where it can land, and with which
// wavelength, follows from the light alone. Scene objects (mirrors, glass,
// diffuse surfaces) will break it; shortcutBlockedBecause must then refuse
// or re-prove each shortcut here.
const char* shortcutPrecondition(Shortcut shortcut) {
  switch (shortcut) {
    case Shortcut::SkipUnreachableLights:
      return "beams travel straight from the light to the camera, so a light behind the sensor or the aperture "
             "plane, facing away, or whose collimated beam misses, never reaches it";
    case Shortcut::AimAtCamera:
      return "beams travel straight from the light to the camera, so every counted beam passes the target sphere "
             "holding the pinhole's disk (or the bare sensor)";
    case Shortcut::TrimSpectrum:
      return "a beam keeps the wavelength it was emitted with, so only the bins the lights' spectra reach are hit";
    case Shortcut::TrimPixels:
      return "beams travel straight from the light to the camera, so they land inside the lights' image through "
             "the pinhole (or a laser's footprint)";
    case Shortcut::ColourFromBins:
      return "a beam's wavelength is drawn independently of where it lands and keeps it, and every traced light "
             "draws from one spectral table, so given its bin a counted beam's wavelength has the table's "
             "distribution inside that bin, and a bin's count times that distribution's mean CMF has the "
             "expectation of the beams' own CMF sums";
  }
  return "";
}

std::string shortcutBlockedBecause(Shortcut /*shortcut*/, const Scene& /*scene*/) {
  // Nothing can stand between a light and the camera in today's scenes
  // (Scene has lights and a camera only), so every precondition holds.
  return "";
}

bool shortcutApplies(Shortcut shortcut, bool requested, const Scene& scene) {
  return requested && shortcutBlockedBecause(shortcut, scene).empty();
}

std::string sharedSpectralTableMissingBecause(std::span<const device::LightRecord> lights,
                                              std::span<const device::SpectralInterval> intervals) {
  auto same = [](const device::SpectralInterval& a, const device::SpectralInterval& b) {
    return a.cdfLow == b.cdfLow && a.lambda0 == b.lambda0 && a.width == b.width && a.slope == b.slope;
  };
  for (size_t l = 1; l < lights.size(); ++l) {
    const auto& first = lights[0];
    const auto& light = lights[l];
    bool equal = light.spectralCount == first.spectralCount;
    for (uint32_t i = 0; equal && i < first.spectralCount; ++i)
      equal = same(intervals[first.spectralFirst + i], intervals[light.spectralFirst + i]);
    if (!equal) return "the traced lights draw from different spectral tables";
  }
  return "";
}

}  // namespace spectrace
