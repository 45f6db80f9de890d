#include "shapes/obj_mesh.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <future>
#include <numbers>
#include <streambuf>
#include <system_error>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <tiny_obj_loader.h>

#include "camera/world_limits.h"
#include "json/input_file.h"
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

// Reads a string in place: tinyobjloader takes an istream, and the file's
// bytes (up to 1 GiB) should not be copied again.
struct StringViewBuf : std::streambuf {
  explicit StringViewBuf(std::string& s) { setg(s.data(), s.data(), s.data() + s.size()); }
};

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ' || s.back() == '.')) s.pop_back();
  return s;
}

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

std::optional<MeshEdgeFault> findEdgeFault(const MeshTriangles& triangles) {
  // Each directed edge as one sortable key: low vertex, high vertex, and
  // whether it runs from high to low (vertex indices < 2^31).
  std::vector<uint64_t> keys;
  keys.reserve(3 * triangles.size());
  for (const auto& t : triangles)
    for (int e = 0; e < 3; ++e) {
      const uint64_t a = t[e], b = t[(e + 1) % 3];
      keys.push_back((std::min(a, b) << 32) | (std::max(a, b) << 1) | uint64_t(a > b));
    }
  std::sort(keys.begin(), keys.end());
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

struct TinyObjMesh {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
};

// tinyobjloader's reading of `text`: the mesh, or its error message.
struct TinyObjReading {
  TinyObjMesh mesh;
  bool parsed = false;
  std::string error, warning;
};

TinyObjReading readWithTinyobj(std::string& text) {
  TinyObjReading reading;
  std::vector<tinyobj::material_t> materials;
  StringViewBuf buffer(text);
  std::istream in(&buffer);
  // No material reader: "mtllib" lines are skipped (surfaces come from
  // the scene). Polygons stay whole: they are split below, where faces
  // keep the file's numbers.
  reading.parsed = tinyobj::LoadObj(&reading.mesh.attrib, &reading.mesh.shapes, &materials, &reading.warning,
                                    &reading.error, &in, nullptr,
                                    /*triangulate=*/false, /*default_vcols_fallback=*/false);
  return reading;
}

struct FanTriangles {
  MeshTriangles triangles;
  std::vector<uint64_t> faceOf;  // each triangle's face number, from 1
  uint64_t faces = 0;
};

// Faces in file order (tinyobjloader's shapes are the file's o/g groups, in
// order), each polygon a fan from its first corner.
FanTriangles fanTriangles(const jf::Source& c, const std::string& ptr, const std::vector<tinyobj::shape_t>& objShapes,
                          size_t vertexCount, uint64_t triangleCount, const std::string& quoted) {
  FanTriangles fan;
  fan.triangles.reserve(triangleCount);
  fan.faceOf.reserve(triangleCount);
  uint64_t& face = fan.faces;
  for (const auto& s : objShapes) {
    size_t next = 0;
    for (unsigned corners : s.mesh.num_face_vertices) {
      ++face;
      std::vector<uint32_t> v(corners);
      for (unsigned k = 0; k < corners; ++k) {
        const int index = s.mesh.indices[next + k].vertex_index;
        if (index < 0 || size_t(index) >= vertexCount)
          c.fail(ptr, fmt::format("{}: face {} refers to vertex {}, but the file has {} vertices{}", quoted, face,
                                  index < 0 ? std::string("before the first") : std::to_string(int64_t(index) + 1),
                                  vertexCount, vertexCount ? fmt::format(" (1 to {})", vertexCount) : ""));
        v[k] = uint32_t(index);
      }
      next += corners;
      for (unsigned k = 1; k + 1 < corners; ++k) {
        fan.triangles.push_back({v[0], v[k], v[k + 1]});
        fan.faceOf.push_back(face);
      }
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
  // The text check and tinyobjloader read the same bytes independently, so
  // they run side by side (each is about a third of a large mesh's load);
  // the check's verdict is still taken first.
  std::future<ObjTextCheck> checking =
      std::async(std::launch::async, [&text] { return checkObjText(text); });
  TinyObjReading reading = readWithTinyobj(text);
  const ObjTextCheck check = checking.get();
  text = std::string();  // up to 1 GiB, not needed after
  if (check.fault)
    c.fail(ptr, fmt::format("{} line {}, {}: {}", quoted, check.fault->line, check.fault->token, check.fault->what));
  if (!reading.parsed) c.fail(ptr, fmt::format("cannot parse {}: {}", quoted, trimmed(reading.error)));
  if (reading.warning.find("Degenerated face") != std::string::npos)
    c.fail(ptr, fmt::format("{} has a face with fewer than 3 vertices", quoted));
  TinyObjMesh& mesh = reading.mesh;
  tinyobj::attrib_t& attrib = mesh.attrib;
  std::vector<tinyobj::shape_t>& objShapes = mesh.shapes;
  const size_t vertexCount = attrib.vertices.size() / 3;
  if (vertexCount > kMaxMeshVertices)
    c.fail(ptr, fmt::format("{} has {} vertices; a mesh has at most {}", quoted, vertexCount, kMaxMeshVertices));
  uint64_t triangleCount = 0;
  for (const auto& s : objShapes)
    for (unsigned corners : s.mesh.num_face_vertices) triangleCount += corners - 2;
  if (triangleCount == 0) c.fail(ptr, fmt::format("{} has no triangles (no faces)", quoted));
  if (triangleCount > maxTriangles)
    c.fail(ptr, fmt::format("{} has {} triangles, more than the {} left of the {} a scene may hold", quoted,
                            triangleCount, maxTriangles, kMaxSceneTriangles));

  FanTriangles fan = fanTriangles(c, ptr, objShapes, vertexCount, triangleCount, quoted);
  MeshTriangles& triangles = fan.triangles;
  const std::vector<uint64_t>& faceOf = fan.faceOf;
  // The text check numbered vertices and faces as tinyobjloader must have:
  // if not, its index checks do not describe this mesh.
  if (vertexCount != check.vertices || fan.faces != check.faces)
    c.fail(ptr, fmt::format("{}: the readers disagree: tinyobjloader read {} vertices and {} faces, the text check "
                            "counted {} and {}",
                            quoted, vertexCount, fan.faces, check.vertices, check.faces));
  objShapes = {};

  std::vector<glm::dvec3> points(vertexCount);
  for (size_t i = 0; i < vertexCount; ++i)
    points[i] = {attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]};
  attrib = tinyobj::attrib_t();
  for (size_t i = 0; i < vertexCount; ++i)
    if (!finite(points[i]))
      c.fail(ptr, fmt::format("{}: vertex {} is not finite ({})", quoted, i + 1, fmtPoint(points[i])));
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
  return notClosed;
}

}  // namespace spectrace
