#pragma once
// The shortcuts the compiler takes, and when each is valid, in one place.
// Every shortcut is on by default, has an option to turn it off (the
// unshortened reference path) and a test against that path. A pass asks
// shortcutApplies() before it acts, so a scene that breaks a precondition
// gets the unshortened path whatever the options say.
#include <span>
#include <string>

#include "device_shared.h"

#include "scene/scene.h"

namespace spectrace {

enum class Shortcut {
  // Lights that provably cannot put a beam on the sensor are never sampled.
  SkipUnreachableLights,
  // Beams are drawn only towards the camera's target sphere, weighted by
  // emission density / sampling density.
  AimAtCamera,
  // The film stores only the wavelength bins the lights can reach.
  TrimSpectrum,
  // The film stores only the rectangle of pixels beams can reach.
  TrimPixels,
  // Exact colour without per-beam colour counters: each bin's count times
  // the mean CMF of the wavelengths the lights' table draws in that bin.
  ColourFromBins,
};

const char* shortcutName(Shortcut shortcut);
// What must hold for the shortcut to be exact, in words (docs and messages).
const char* shortcutPrecondition(Shortcut shortcut);
// Why the shortcut is not valid for `scene`, or "" when it is.
std::string shortcutBlockedBecause(Shortcut shortcut, const Scene& scene);
// Whether a pass may take the shortcut: asked for, and valid for the scene.
bool shortcutApplies(Shortcut shortcut, bool requested, const Scene& scene);

// Whether two spectral tables are the same, bit for bit (so their draws
// are): lights whose tables are the same share one copy
// (compile_scene.cpp), and ColourFromBins asks it of every traced light.
bool sameSpectralTable(std::span<const device::SpectralInterval> a, std::span<const device::SpectralInterval> b);

// ColourFromBins also needs every traced light to draw its wavelengths from
// one and the same spectral table: why not, or "" when they do.
std::string sharedSpectralTableMissingBecause(std::span<const device::LightRecord> lights,
                                              std::span<const device::SpectralInterval> intervals);

}  // namespace spectrace
