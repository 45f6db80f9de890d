#include "compile/shortcuts.h"

#include <cstring>

#include <fmt/format.h>

#include "materials/material_type.h"

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

// Without objects every precondition holds: a beam travels in a straight
// line from its light to the sensor with the wavelength it was emitted
// with. Objects can break them; shortcutBlockedBecause below decides, for
// each shortcut, which objects do, and turns the shortcut off for them.
const char* shortcutPrecondition(Shortcut shortcut) {
  switch (shortcut) {
    case Shortcut::SkipUnreachableLights:
      return "beams travel straight from the light to the camera (objects, if any, are absorbers, which only take "
             "beams away), so a light behind the sensor or the aperture plane, facing away, or whose collimated beam "
             "misses, never reaches it";
    case Shortcut::AimAtCamera:
      return "beams travel straight from the light to the camera (objects, if any, are absorbers), so every "
             "counted beam passes the target sphere holding the pinhole's disk (or the bare sensor)";
    case Shortcut::TrimSpectrum:
      return "a beam keeps the wavelength it was emitted with (no material shifts it), so only the bins the lights' "
             "spectra reach are hit";
    case Shortcut::TrimPixels:
      return "beams travel straight from the light to the camera (objects, if any, are absorbers), so they land "
             "inside the lights' image through the pinhole (or a laser's footprint), and so do camera paths that "
             "see a light; light paths give the same bits, camera paths (spread over the stored pixels only) the "
             "same expectation";
    case Shortcut::ColourFromBins:
      return "a beam's wavelength is drawn independently of where it lands and keeps it (no object's effect "
             "depends on the wavelength: no varying reflectance, no dispersive glass), and every traced light "
             "draws from one spectral table, so given its bin a counted beam's wavelength has the table's "
             "distribution inside that bin, and a bin's count times that distribution's mean CMF has the "
             "expectation of the beams' own CMF sums";
  }
  return "";
}

namespace {

// The first object that can send a beam somewhere a straight line from its
// light would not go: anything but an absorber (an absorber only takes beams
// away, so every argument about where beams can land still holds).
std::string redirectingObject(const Scene& scene) {
  for (const SceneObject& object : scene.objects)
    if (materialTypeUnit(object.material.type).redirectsBeams)
      return fmt::format("{} is a {} {}, which can send a beam to the camera along a path that is not a straight line "
                         "from its light",
                         object.label, materialTypeName(object.material.type), shapeTypeName(object.shape.type));
  return "";
}

// The first object whose effect on a beam depends on its wavelength: a
// reflectance that varies, or a dispersive dielectric.
std::string wavelengthDependentObject(const Scene& scene) {
  for (const SceneObject& object : scene.objects) {
    const SurfaceMaterial& m = object.material;
    if (materialTypeUnit(m.type).variesWithWavelength(m))
      return fmt::format("{} ({} {}) treats wavelengths differently, so where a beam lands depends on its wavelength",
                         object.label, materialTypeName(m.type), shapeTypeName(object.shape.type));
  }
  return "";
}

}  // namespace

std::string shortcutBlockedBecause(Shortcut shortcut, const Scene& scene) {
  switch (shortcut) {
    case Shortcut::SkipUnreachableLights:
    case Shortcut::AimAtCamera:
    case Shortcut::TrimPixels:
      return redirectingObject(scene);
    case Shortcut::TrimSpectrum:
      return "";  // no material changes a beam's wavelength
    case Shortcut::ColourFromBins:
      return wavelengthDependentObject(scene);
  }
  return "";
}

bool shortcutApplies(Shortcut shortcut, bool requested, const Scene& scene) {
  return requested && shortcutBlockedBecause(shortcut, scene).empty();
}

bool sameSpectralTable(std::span<const device::SpectralInterval> a, std::span<const device::SpectralInterval> b) {
  static_assert(sizeof(device::SpectralInterval) == 24, "memcmp below compares padding-free records");
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(device::SpectralInterval)) == 0;
}

std::string sharedSpectralTableMissingBecause(std::span<const device::LightRecord> lights,
                                              std::span<const device::SpectralInterval> intervals) {
  const auto tableOf = [&](const device::LightRecord& light) {
    return intervals.subspan(light.spectralFirst, light.spectralCount);
  };
  for (size_t l = 1; l < lights.size(); ++l)
    if (!sameSpectralTable(tableOf(lights[0]), tableOf(lights[l])))
      return "the traced lights draw from different spectral tables";
  return "";
}

}  // namespace spectrace
