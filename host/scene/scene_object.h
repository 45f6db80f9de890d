#pragma once
// Objects a scene places between its lights and its camera: a shape with a
// material, each kind of either a unit (shapes/shape_type.h,
// materials/material_type.h). The kernel's side is shaders/transport.h; the
// compiler turns shapes into primitives (device_shared.h) and builds the BVH
// over them.
#include <string>

#include "materials/material.h"
#include "shapes/shape.h"

namespace spectrace {

struct SceneObject {
  std::string label;  // JSON pointer, e.g. "/objects/2", for messages
  std::string name;   // optional "name"
  Shape shape;
  SurfaceMaterial material;
};

}  // namespace spectrace
