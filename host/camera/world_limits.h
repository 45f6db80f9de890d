#pragma once
// Bounds on world geometry, shared by everything placed in a scene (the
// camera, the lights) so that files and scenes built in code get the same.

namespace spectrace {

// Bound on coordinates and lengths (metres): far beyond any sensible scene,
// far inside float range, so the single-precision device math stays finite.
inline constexpr double kMaxCoordinateM = 1e12;
// |cross(a, b)| of unit vectors below this: a and b are collinear.
inline constexpr double kCollinearEps = 1e-9;

}  // namespace spectrace
