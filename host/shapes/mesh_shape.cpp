// A triangle mesh from a Wavefront OBJ file: "file" and an optional
// "transform" (shapes/obj_mesh.h reads it). It emits one triangle primitive
// per triangle; it bounds a solid when every edge is shared by two
// triangles running along it in opposite directions, facing outwards.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "camera/world_limits.h"
#include "lights/light_shared.h"
#include "shapes/obj_mesh.h"
#include "shapes/shape_shared.h"

namespace spectrace {

namespace {

namespace fs = std::filesystem;
namespace jf = json_fields;

MeshTransform parseTransform(const jf::Source& c, const jf::Json& v, const std::string& p) {
  jf::checkObject(c, v, p, {"translate", "rotate_deg", "scale"}, "a transform");
  MeshTransform t;
  if (auto* x = jf::find(v, "translate")) t.translate = jf::getPoint(c, *x, jf::child(p, "translate"), kMaxCoordinateM);
  if (auto* x = jf::find(v, "rotate_deg")) t.rotateDeg = jf::getVec3(c, *x, jf::child(p, "rotate_deg"));
  if (auto* x = jf::find(v, "scale")) {
    const std::string sp = jf::child(p, "scale");
    const auto factor = [&](const jf::Json& e, const std::string& ep) {
      const double s = jf::getNumber(c, e, ep);
      if (s == 0.0) c.fail(ep, "must be a finite number other than 0 (a negative factor mirrors)");
      return s;
    };
    if (x->is_number()) {
      t.scale = glm::dvec3(factor(*x, sp));
    } else if (x->is_array() && x->size() == 3) {
      for (size_t i = 0; i < 3; ++i) t.scale[int(i)] = factor((*x)[i], jf::child(sp, i));
    } else {
      c.fail(sp, fmt::format("must be a number or an array of 3 numbers [sx, sy, sz] (got {})", jf::describe(*x)));
    }
  }
  return t;
}

void parse(const jf::Source& c, const jf::Json& v, const std::string& p, const ShapeReading& reading, Shape& shape) {
  const std::string fp = jf::child(p, "file");
  const std::string rel = jf::getString(c, jf::require(c, v, p, "file", " (an OBJ file)"), fp);
  MeshTransform transform;
  if (auto* t = jf::find(v, "transform")) transform = parseTransform(c, *t, jf::child(p, "transform"));
  const fs::path path(rel);
  const fs::path resolved = c.resolve(path);
  const std::string notClosed = loadObjMesh(c, fp, resolved, rel, transform, reading.trianglesLeft, shape);
  if (reading.closedFor && !notClosed.empty())
    c.fail(reading.materialPtr, needsClosedShape(reading.closedFor, fmt::format("; {} is not closed: {}",
                                                                                 jf::jsonQuoted(rel), notClosed)));
}

void validate(const Shape& shape, const ShapeFieldCheck& check) {
  const auto& vertices = shape.vertices;
  const auto& triangles = shape.triangles;
  if (triangles.empty()) check.fail("triangles", "a mesh needs at least one triangle");
  if (vertices.size() > kMaxMeshVertices)
    check.fail("vertices", fmt::format("has {} vertices; a mesh has at most {}", vertices.size(), kMaxMeshVertices));
  for (size_t i = 0; i < vertices.size(); ++i) {
    const glm::dvec3& p = vertices[i];
    if (!allFinite(p) || std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) > kMaxCoordinateM)
      check.fail(fmt::format("vertices/{}", i),
                 fmt::format("must be finite with every coordinate's magnitude <= {:g} m (got [{}, {}, {}])",
                             kMaxCoordinateM, jf::fmtNum(p.x), jf::fmtNum(p.y), jf::fmtNum(p.z)));
  }
  for (size_t k = 0; k < triangles.size(); ++k)
    for (uint32_t v : triangles[k])
      if (v >= vertices.size())
        check.fail(fmt::format("triangles/{}", k),
                   fmt::format("refers to vertex {}, but the mesh has {} vertices", v, vertices.size()));
  if (auto k = findDegenerateTriangle(vertices, triangles))
    check.fail(fmt::format("triangles/{}", *k), fmt::format("has zero area (vertices {}, {}, {})", triangles[*k][0],
                                                            triangles[*k][1], triangles[*k][2]));
}

std::string notClosedBecause(const Shape& shape, std::string_view material) {
  if (auto fault = findEdgeFault(shape.triangles))
    return needsClosedShape(material, "; this mesh is not closed: " + describeEdgeFault(*fault, 0, [](size_t k) {
                                        return fmt::format("triangle {}", k);
                                      }));
  // Consistent winding can still be inside out: glass then refracts every
  // beam the wrong way. Outward faces enclose a positive signed volume.
  double volume6 = 0.0;  // six times the signed volume
  for (const auto& t : shape.triangles)
    volume6 += glm::dot(shape.vertices[t[0]], glm::cross(shape.vertices[t[1]], shape.vertices[t[2]]));
  if (!(volume6 > 0.0)) {
    const std::string mesh = shape.meshFile.empty() ? "this mesh" : jf::jsonQuoted(shape.meshFile.string());
    return fmt::format("a {} mesh must face outwards (counter-clockwise seen from outside), but {}'s faces enclose a "
                       "signed volume of {:g} m^3; turn every face round",
                       material, mesh, volume6 / 6.0);
  }
  return "";
}

// Returns false, placing nothing, for a triangle whose float edges are
// parallel: validation refuses zero area in double, but a sliver can still
// lose it in float, and its normal would be NaN. Beams could not meet it.
bool placeTriangle(const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2, uint32_t material,
                   PlacedPrimitive& placed) {
  device::Primitive& p = placed.primitive;
  p.type = device::kPrimitiveTriangle;
  p.material = material;
  p.a = toFloat(v0);
  p.b = toFloat(v1 - v0);
  p.c = toFloat(v2 - v0);
  const glm::vec3 n = glm::cross(p.b, p.c);
  // (1e-30 m^4: an area below 1e-15 m^2, whose normal's length would
  // underflow when the kernel squares it.)
  if (!(glm::dot(n, n) > 1e-30f) || !std::isfinite(glm::dot(n, n))) return false;
  const glm::dvec3 a = toDouble(p.a);
  placed.bounds = boundsOfPoints({a, a + toDouble(p.b), a + toDouble(p.c)});
  return true;
}

void place(const Shape& shape, const CameraFrame& frame, uint32_t material, std::vector<PlacedPrimitive>& out) {
  // The camera frame (right = forward x up, up, forward) is a mirror image
  // of the world, so a triangle's corners are taken in the other order
  // there: counter-clockwise from outside stays outwards.
  // Each vertex is moved once, not once for each triangle it is a corner of
  // (about six in a closed mesh): the same numbers.
  std::vector<glm::dvec3> local(shape.vertices.size());
  for (size_t i = 0; i < local.size(); ++i) local[i] = frame.pointToLocal(shape.vertices[i]);
  out.reserve(out.size() + shape.triangles.size());
  for (const auto& t : shape.triangles) {
    PlacedPrimitive triangle;
    if (placeTriangle(local[t[0]], local[t[2]], local[t[1]], material, triangle)) out.push_back(triangle);
  }
}

}  // namespace

const ShapeTypeUnit& meshShapeUnit() {
  static const ShapeTypeUnit unit{
      .type = ShapeType::Mesh,
      .name = "mesh",
      .keys = {"file", "transform"},
      .parse = parse,
      .validate = validate,
      .notClosedBecause = notClosedBecause,
      .place = place,
  };
  return unit;
}

}  // namespace spectrace
