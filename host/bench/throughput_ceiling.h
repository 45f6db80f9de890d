#pragma once
// The ceiling kernel's scene (backend/ceiling.h) for the bench: the
// throughput scene's geometry and spectrum.
#include "backend/ceiling.h"

namespace spectrace {

// D65 at 1 nm over 360-830 nm, 64 bins, a disk of radius 0.05 m at 0.1 m
// before a bare 0.1 m, 512x512 sensor.
CeilingScene throughputCeilingScene();

}  // namespace spectrace
