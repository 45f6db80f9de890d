#pragma once
// Inside the shapes module: triangle meshes, for the mesh unit
// (mesh_shape.cpp). Reading Wavefront OBJ files (obj_text.h) into a mesh
// object's shape, in world coordinates, and the checks on triangles that
// meshes built in code get too.
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "json/json_fields.h"
#include "shapes/shape.h"

namespace spectrace {

// An OBJ file is at most this big: the most triangles a scene may hold
// (kMaxSceneTriangles) written as text, with room to spare.
inline constexpr uint64_t kMaxObjFileBytes = uint64_t(1) << 30;  // 1 GiB
// Vertex numbers fit in 31 bits (OBJ indices are C ints; the edge check packs
// two of them in 64 bits).
inline constexpr uint64_t kMaxMeshVertices = uint64_t(1) << 31;

// A mesh object's "transform": scale, then rotate about x, then y, then z
// (degrees, right-handed), then translate.
struct MeshTransform {
  glm::dvec3 scale{1.0};
  glm::dvec3 rotateDeg{0.0};
  glm::dvec3 translate{0.0};
};

// The points placed by `transform`, in order. Rotations by whole multiples
// of 90 degrees are exact. When the scale mirrors (an odd number of negative
// factors) triangles must be turned around to keep facing outwards; see
// mirrors().
std::vector<glm::dvec3> placePoints(const MeshTransform& transform, std::vector<glm::dvec3> points);
bool mirrors(const MeshTransform& transform);

// Reads the OBJ file `path` (written `asWritten` in the scene, whose field
// is `ptr`): its positions and faces, each polygon split into a fan from its
// first corner (so polygons must be convex). shape.vertices are all the
// file's positions in its order (vertex k is the file's vertex k + 1) placed
// by `transform`; shape.triangles, shape.closed and shape.meshFile. Every
// problem is c.fail(ptr, ...), naming faces and vertices as the file numbers
// them: an unreadable file, a refused token of a `v`, `f`, `l` or `p` line
// (readObjText, obj_text.h: the line and the token are named), no
// triangles, more than `maxTriangles`, a placed vertex that is not finite
// or lies outside the world bounds, a triangle of zero area. Returns "" when the mesh is closed, else why not
// (for a dielectric's message).
std::string loadObjMesh(const json_fields::Source& c, const std::string& ptr, const std::filesystem::path& path,
                        const std::string& asWritten, const MeshTransform& transform, uint64_t maxTriangles,
                        Shape& shape);
// The same for the file's text, already read (shape.meshFile is left as it
// is).
std::string parseObjMesh(const json_fields::Source& c, const std::string& ptr, std::string text,
                         const std::string& asWritten, const MeshTransform& transform, uint64_t maxTriangles,
                         Shape& shape);

using MeshTriangles = std::vector<std::array<uint32_t, 3>>;

// An edge that keeps a mesh from bounding a solid. Triangle (a, b, c) runs
// along its edges a->b, b->c, c->a.
struct MeshEdgeFault {
  enum class Kind {
    Open,           // one triangle has it: a hole
    SameDirection,  // two triangles run along it the same way: one is flipped
    Shared,         // more than two triangles have it
  };
  Kind kind = Kind::Open;
  uint32_t from = 0, to = 0;      // vertex indices, as `triangles[0]` runs along it
  std::vector<size_t> triangles;  // those that have it (at most 3 listed)
};

// The first edge (in vertex order) that is not used by exactly two
// triangles running along it in opposite directions; nullopt when every
// edge is, so the mesh bounds a solid.
std::optional<MeshEdgeFault> findEdgeFault(const MeshTriangles& triangles);
// "the edge between vertices 3 and 7 belongs to face 5 only (a hole)", ...:
// vertices numbered from `firstVertex` (1 for OBJ files), triangles named by
// `faceName` ("face 5", "triangle 4").
std::string describeEdgeFault(const MeshEdgeFault& fault, uint32_t firstVertex,
                              const std::function<std::string(size_t triangle)>& faceName);

// The first triangle whose corners span no area in double (repeated or
// collinear corners), or nullopt. Indices must be in range.
std::optional<size_t> findDegenerateTriangle(const std::vector<glm::dvec3>& vertices, const MeshTriangles& triangles);

}  // namespace spectrace
