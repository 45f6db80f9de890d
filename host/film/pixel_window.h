#pragma once
// The window proof: the rectangle of sensor pixels that beams from the
// given lights can land on, when beams travel straight from a light to the
// camera (compile/shortcuts.h, TrimPixels).
#include <span>

#include "camera/camera.h"
#include "film/film_layout.h"
#include "lights/light_type.h"

namespace spectrace {

// The pixels any counted beam from `lights` can land on, plus a pixel of
// margin for float rounding; the whole sensor when that cannot be bounded.
PixelWindow reachablePixelWindow(const Camera& camera, std::span<const LightReach> lights);

}  // namespace spectrace
