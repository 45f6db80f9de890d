#include "scene/scene_object.h"

namespace spectrace {

const char* shapeTypeName(ShapeType type) {
  switch (type) {
    case ShapeType::Rect: return "rect";
    case ShapeType::Disk: return "disk";
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Mesh: return "mesh";
  }
  return "unknown";
}

}  // namespace spectrace
