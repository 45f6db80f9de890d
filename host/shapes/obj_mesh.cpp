#include "shapes/obj_mesh.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <future>
#include <numbers>
#include <system_error>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "camera/world_limits.h"
#include "json/input_file.h"
#include "json/sha256.h"
#include "shapes/obj_text.h"

namespace spectrace {

namespace fs = std::filesystem;
namespace jf = json_fields;

namespace {

struct SinCos {
  double s, c;
};

// Exact at whole multiples of 90 degrees, so a quarter turn moves vertices
// onto exact coordinates.
SinCos sinCosDeg(double deg) {
  const double reduced = std::fmod(deg, 360.0);  // exact
  const double quarters = reduced / 90.0;
  if (quarters == std::round(quarters)) {
    static constexpr SinCos kQuarter[4] = {{0.0, 1.0}, {1.0, 0.0}, {0.0, -1.0}, {-1.0, 0.0}};
    return kQuarter[((int(quarters) % 4) + 4) % 4];
  }
  const double radians = reduced * (std::numbers::pi / 180.0);
  return {std::sin(radians), std::cos(radians)};
}

std::string fmtPoint(const glm::dvec3& p) {
  return fmt::format("[{}, {}, {}]", jf::fmtNum(p.x), jf::fmtNum(p.y), jf::fmtNum(p.z));
}

bool finite(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

std::string joinFaces(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return out;
}

}  // namespace

std::vector<glm::dvec3> placePoints(const MeshTransform& t, std::vector<glm::dvec3> points) {
  const SinCos rx = sinCosDeg(t.rotateDeg.x), ry = sinCosDeg(t.rotateDeg.y), rz = sinCosDeg(t.rotateDeg.z);
  for (glm::dvec3& p : points) {
    glm::dvec3 q = p * t.scale;
    q = {q.x, rx.c * q.y - rx.s * q.z, rx.s * q.y + rx.c * q.z};
    q = {ry.c * q.x + ry.s * q.z, q.y, -ry.s * q.x + ry.c * q.z};
    q = {rz.c * q.x - rz.s * q.y, rz.s * q.x + rz.c * q.y, q.z};
    p = q + t.translate;
  }
  return points;
}

bool mirrors(const MeshTransform& t) { return ((t.scale.x < 0.0) != (t.scale.y < 0.0)) != (t.scale.z < 0.0); }

namespace {

// Directed edge e of triangle t as one sortable key: low vertex, high
// vertex, and whether it runs from high to low (vertex indices < 2^31).
uint64_t edgeKey(const std::array<uint32_t, 3>& t, int e) {
  const uint64_t a = t[e], b = t[(e + 1) % 3];
  return (std::min(a, b) << 32) | (std::max(a, b) << 1) | uint64_t(a > b);
}

// Every edge's key, in ascending order. A mesh's vertices are few and each
// is the low vertex of a handful of edges, so the keys are counted into one
// bucket per low vertex and each bucket sorted: the order std::sort gives,
// in two passes over the edges (a million-triangle mesh's sort took longer
// than reading its file in parts). Indices far beyond the edges' count (not
// a mesh's) are sorted whole.
std::vector<uint64_t> sortedEdgeKeys(const MeshTriangles& triangles) {
  const size_t edges = 3 * triangles.size();
  std::vector<uint64_t> keys(edges);
  uint32_t highest = 0;
  for (const auto& t : triangles) highest = std::max({highest, t[0], t[1], t[2]});
  if (highest > edges) {
    for (size_t k = 0; k < triangles.size(); ++k)
      for (int e = 0; e < 3; ++e) keys[3 * k + size_t(e)] = edgeKey(triangles[k], e);
    std::sort(keys.begin(), keys.end());
    return keys;
  }
  std::vector<size_t> bucketEnd(size_t(highest) + 2, 0);  // [v + 1]: keys of low vertex <= v
  for (const auto& t : triangles)
    for (int e = 0; e < 3; ++e) ++bucketEnd[size_t(std::min(t[e], t[(e + 1) % 3])) + 1];
  for (size_t v = 1; v < bucketEnd.size(); ++v) bucketEnd[v] += bucketEnd[v - 1];
  std::vector<size_t> next(bucketEnd.begin(), bucketEnd.end() - 1);  // each bucket's next free place
  for (const auto& t : triangles)
    for (int e = 0; e < 3; ++e) {
      const uint64_t key = edgeKey(t, e);
      keys[next[size_t(key >> 32)]++] = key;
    }
  for (size_t v = 0; v + 1 < bucketEnd.size(); ++v)
    std::sort(keys.begin() + bucketEnd[v], keys.begin() + bucketEnd[v + 1]);
  return keys;
}

}  // namespace

std::optional<MeshEdgeFault> findEdgeFault(const MeshTriangles& triangles) {
  const std::vector<uint64_t> keys = sortedEdgeKeys(triangles);
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && (keys[j] >> 1) == (keys[i] >> 1)) ++j;
    const size_t count = j - i;
    if (count == 2 && (keys[i] & 1) != (keys[i + 1] & 1)) {
      i = j;
      continue;
    }
    MeshEdgeFault fault;
    fault.kind = count == 1 ? MeshEdgeFault::Kind::Open
                 : count == 2 ? MeshEdgeFault::Kind::SameDirection
                              : MeshEdgeFault::Kind::Shared;
    const uint32_t lo = uint32_t(keys[i] >> 32), hi = uint32_t((keys[i] >> 1) & 0x7fffffffu);
    for (size_t k = 0; k < triangles.size() && fault.triangles.size() < 3; ++k)
      for (int e = 0; e < 3; ++e) {
        const uint32_t a = triangles[k][e], b = triangles[k][(e + 1) % 3];
        if (std::min(a, b) == lo && std::max(a, b) == hi) {
          if (fault.triangles.empty()) fault.from = a, fault.to = b;
          fault.triangles.push_back(k);
          break;
        }
      }
    return fault;
  }
  return std::nullopt;
}

std::string describeEdgeFault(const MeshEdgeFault& fault, uint32_t firstVertex,
                              const std::function<std::string(size_t)>& faceName) {
  const uint64_t from = uint64_t(fault.from) + firstVertex, to = uint64_t(fault.to) + firstVertex;
  const uint64_t low = std::min(from, to), high = std::max(from, to);
  std::vector<std::string> faces;  // two triangles of one polygon are one face
  for (size_t t : fault.triangles)
    if (std::string name = faceName(t); std::find(faces.begin(), faces.end(), name) == faces.end())
      faces.push_back(std::move(name));
  switch (fault.kind) {
    case MeshEdgeFault::Kind::Open:
      return fmt::format("the edge between vertices {} and {} belongs to {} only (the mesh has a hole there)", low,
                         high, joinFaces(faces));
    case MeshEdgeFault::Kind::SameDirection:
      return fmt::format("{} both run from vertex {} to vertex {} (one of them is flipped: seen from outside, every "
                         "face must run counter-clockwise)",
                         joinFaces(faces), from, to);
    case MeshEdgeFault::Kind::Shared:
      break;
  }
  return fmt::format("the edge between vertices {} and {} belongs to more than two faces ({}, ...)", low, high,
                     joinFaces(faces));
}

std::optional<size_t> findDegenerateTriangle(const std::vector<glm::dvec3>& vertices, const MeshTriangles& triangles) {
  for (size_t k = 0; k < triangles.size(); ++k) {
    const glm::dvec3& a = vertices[triangles[k][0]];
    const glm::dvec3 n = glm::cross(vertices[triangles[k][1]] - a, vertices[triangles[k][2]] - a);
    if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0) return k;
  }
  return std::nullopt;
}

namespace {

// The file's bytes; a missing or unreadable file is c.fail(ptr, ...).
std::string readObjFile(const jf::Source& c, const std::string& ptr, const fs::path& path,
                        const std::string& asWritten) {
  const std::string quoted = jf::jsonQuoted(asWritten);
  // "No such file or directory" with where it was looked for, as for CSV
  // spectra; readInputFile's checks (a regular file, the size) follow.
  struct stat st{};
  // A scene developed from a state reads its meshes from the state, not the disk.
  if (!BundledInputFiles::active() && ::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    std::error_code ec;
    const std::string where =
        fs::path(asWritten).is_absolute()
            ? std::string()
            : fmt::format(" (looked for {}, relative to the scene file's folder)",
                          jf::jsonQuoted(fs::absolute(path, ec).string()));
    c.fail(ptr, fmt::format("cannot read {}: {}{}", quoted, std::error_code(err, std::generic_category()).message(),
                            where));
  }
  try {
    return readInputFile(path, "OBJ file", kMaxObjFileBytes);
  } catch (const InputFileError& e) {
    c.fail(ptr, fmt::format("cannot read {}: {}", quoted, e.reason));
  }
}

struct FanTriangles {
  MeshTriangles triangles;
  std::vector<uint64_t> faceOf;  // each triangle's face number, from 1
};

// Faces in file order, each polygon a fan from its first corner.
FanTriangles fanTriangles(const jf::Source& c, const std::string& ptr, const ObjText& obj, uint64_t triangleCount,
                          const std::string& quoted) {
  FanTriangles fan;
  fan.triangles.reserve(triangleCount);
  fan.faceOf.reserve(triangleCount);
  const size_t vertexCount = obj.vertices.size();
  size_t next = 0;
  for (size_t face = 0; face < obj.cornerCounts.size(); ++face) {
    const uint32_t* v = obj.corners.data() + next;
    const uint32_t corners = obj.cornerCounts[face];
    next += corners;
    // readObjText has checked every index against the file's vertices; the
    // mesh's memory safety should not rest on that alone.
    for (uint32_t k = 0; k < corners; ++k)
      if (v[k] >= vertexCount)
        c.fail(ptr, fmt::format("{}: face {} refers to vertex {}, but the file has {} vertices", quoted, face + 1,
                                uint64_t(v[k]) + 1, vertexCount));
    for (uint32_t k = 1; k + 1 < corners; ++k) {
      fan.triangles.push_back({v[0], v[k], v[k + 1]});
      fan.faceOf.push_back(face + 1);
    }
  }
  return fan;
}

}  // namespace

std::string loadObjMesh(const jf::Source& c, const std::string& ptr, const fs::path& path, const std::string& asWritten,
                        const MeshTransform& transform, uint64_t maxTriangles, Shape& shape) {
  const std::string notClosed =
      parseObjMesh(c, ptr, readObjFile(c, ptr, path, asWritten), asWritten, transform, maxTriangles, shape);
  shape.meshFile = path;
  return notClosed;
}

std::string parseObjMesh(const jf::Source& c, const std::string& ptr, std::string text, const std::string& asWritten,
                         const MeshTransform& transform, uint64_t maxTriangles, Shape& shape) {
  const std::string quoted = jf::jsonQuoted(asWritten);
  ObjText obj = readObjText(text);
  if (obj.fault)
    c.fail(ptr, fmt::format("{} line {}, {}: {}", quoted, obj.fault->line, obj.fault->token, obj.fault->what));
  // The digest of the bytes just read (the scene's fingerprint holds it),
  // taken on another thread while this one checks and places the mesh, which
  // it does alone; the text (up to 1 GiB) goes with it and is freed there.
  // (Policy async | deferred: where no thread can start, the hash runs at
  // get() instead.)
  std::future<std::string> digest = std::async(std::launch::async | std::launch::deferred,
                                               [bytes = std::move(text)] { return sceneSha256Hex(bytes); });
  const size_t vertexCount = obj.vertices.size();
  if (vertexCount > kMaxMeshVertices)
    c.fail(ptr, fmt::format("{} has {} vertices; a mesh has at most {}", quoted, vertexCount, kMaxMeshVertices));
  uint64_t triangleCount = 0;
  for (uint32_t corners : obj.cornerCounts) triangleCount += corners - 2;
  if (triangleCount == 0) c.fail(ptr, fmt::format("{} has no triangles (no faces)", quoted));
  if (triangleCount > maxTriangles)
    c.fail(ptr, fmt::format("{} has {} triangles, more than the {} left of the {} a scene may hold", quoted,
                            triangleCount, maxTriangles, kMaxSceneTriangles));

  FanTriangles fan = fanTriangles(c, ptr, obj, triangleCount, quoted);
  MeshTriangles& triangles = fan.triangles;
  const std::vector<uint64_t>& faceOf = fan.faceOf;
  obj.corners = {};
  obj.cornerCounts = {};
  const std::vector<glm::dvec3> points = std::move(obj.vertices);  // finite, as readObjText reads them
  const bool identity = transform.scale == glm::dvec3(1.0) && transform.rotateDeg == glm::dvec3(0.0) &&
                        transform.translate == glm::dvec3(0.0);
  std::vector<glm::dvec3> placed = placePoints(transform, points);
  for (size_t i = 0; i < vertexCount; ++i) {
    const glm::dvec3& p = placed[i];
    if (!finite(p) || std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) > kMaxCoordinateM)
      c.fail(ptr, fmt::format("{}: vertex {} lies at {}{}; world coordinates must be finite with magnitude <= {:g} m",
                              quoted, i + 1, fmtPoint(p),
                              identity ? "" : fmt::format(" after the transform ({} in the file)", fmtPoint(points[i])),
                              kMaxCoordinateM));
  }
  // A mirroring scale turns faces inside out: turn them back.
  if (mirrors(transform))
    for (auto& t : triangles) std::swap(t[1], t[2]);

  if (auto k = findDegenerateTriangle(placed, triangles)) {
    const auto& t = triangles[*k];
    c.fail(ptr, fmt::format("{}: face {} has zero area: its corners, vertices {}, {} and {}, lie at {}, {} and {}{}",
                            quoted, faceOf[*k], t[0] + 1, t[1] + 1, t[2] + 1, fmtPoint(placed[t[0]]),
                            fmtPoint(placed[t[1]]), fmtPoint(placed[t[2]]), identity ? "" : " after the transform"));
  }

  std::string notClosed;
  if (auto fault = findEdgeFault(triangles))
    notClosed = describeEdgeFault(*fault, 1, [&](size_t k) { return fmt::format("face {}", faceOf[k]); });
  shape.vertices = std::move(placed);
  shape.triangles = std::move(triangles);
  shape.closed = notClosed.empty();
  shape.meshSha256 = digest.get();
  return notClosed;
}

}  // namespace spectrace
