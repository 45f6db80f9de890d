#pragma once
// Bounds on scene values, enforced by validateScene (and named in the
// loader's messages), so files and scenes built in code get the same.
#include <cstdint>

#include "camera/world_limits.h"
#include "shapes/shape.h"

namespace spectrace {

inline constexpr int kMaxPixelsPerAxis = 65535;
inline constexpr int64_t kMaxPixelsTotal = int64_t(1) << 28;
inline constexpr int kMaxBins = 100000;
inline constexpr double kMinWavelengthNm = 1.0;       // soft X-rays; keeps Planck's law and bin widths finite
inline constexpr double kMaxWavelengthNm = 100000.0;  // 0.1 mm; keeps spectral tables finite
// Each light costs a few KB to compile and its spectral table on the device;
// real scenes have a handful.
inline constexpr int kMaxLights = 4096;
inline constexpr double kMaxKelvin = 1e6;  // hotter than any star; keeps Planck's law finite
// Objects: far above hand-made scenes and scanned models (their triangles:
// kMaxSceneTriangles, shapes/shape.h).
inline constexpr int kMaxObjects = 100000;
// Surfaces a beam may scatter from: beyond this a beam's weight is long gone.
inline constexpr int kMaxBounces = 1024;

}  // namespace spectrace
