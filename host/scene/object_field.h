#pragma once
// Inside the scene module: reading an entry of the "objects" array.
#include <cstdint>
#include <string>
#include <vector>

#include "json/json_fields.h"
#include "scene/scene.h"

namespace spectrace {

// Reads the object `v` at `ptr` (its shape, its material, and for a mesh its
// OBJ file, of at most `trianglesLeft` triangles, which it counts down).
// An object with "emission" also appends that light (type object) to
// `emitters`, as the emission of object objectIndex.
// Value rules are validateScene's; what needs the file to say well (a mesh's
// faces, a dielectric on an open mesh) is checked here.
SceneObject parseObject(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr,
                        const SpectrumRange& range, uint64_t& trianglesLeft, size_t objectIndex,
                        std::vector<Light>& emitters);

}  // namespace spectrace
