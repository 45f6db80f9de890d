// Emitting object: an object's "emission" (scene/object_field.cpp reads
// it), a Lambertian emitter over the object's whole surface, one-sided
// along the surface's normals (outwards for a sphere or a closed mesh, a
// rect's or disk's `normal`, a triangle's counter-clockwise face) or
// two-sided. The object still blocks and scatters beams as its material
// says: the kernel starts each beam just off the surface it leaves.
//
// Radiance is uniform over the surface: each beam starts at a point drawn
// uniformly by area (a primitive through an alias table by area, O(1) in
// the triangle count, then a uniform point on it) and leaves
// cosine-weighted about the face it leaves, with the light's power shared
// equally among beams. Exact up to the float areas of the primitives the
// BVH holds, which are the surface the beams start on.
#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "json/scene_error.h"
#include "lights/light_shared.h"
#include "spectrum/alias_table.h"
#include "spectrum/wavelength_sampler.h"

namespace spectrace {

const LightTypeUnit& objectLightUnit();  // below; the table is lights/light_types.cpp

namespace {

namespace jf = json_fields;

void parse(const jf::Source&, const jf::Json&, const std::string& ptr, Light&) {
  throw std::logic_error(ptr + ": an object's emission is read with its object");
}

void validate(const Light&, const LightFieldCheck&) {}

// A primitive's area in double, from the float values the kernel samples.
double primitiveArea(const device::Primitive& p) {
  const glm::dvec3 b(p.b), c(p.c);
  switch (p.type) {
    case device::kPrimitiveTriangle: return 0.5 * glm::length(glm::cross(b, c));
    case device::kPrimitiveRect: return 4.0 * glm::length(glm::cross(b, c));
    case device::kPrimitiveDisk: return std::numbers::pi * double(p.c.x);
    case device::kPrimitiveSphere: return 4.0 * std::numbers::pi * double(p.b.x) * double(p.b.x);
    default: throw std::logic_error("an emitting object has a primitive of unknown type");
  }
}

// The scene data (device_shared.h, kObjectEmitterHeaderWords).
void pack(const Light& light, const CameraFrame& frame, device::LightRecord& record, SceneData& data) {
  const std::vector<device::Primitive> primitives = light.surface->place(frame);
  std::vector<double> areas;
  areas.reserve(primitives.size());
  for (const device::Primitive& p : primitives) areas.push_back(primitiveArea(p));
  // Validation refuses shapes without area in double; a mesh of float
  // slivers alone (each placed as nothing) can still have none.
  if (primitives.empty() || !(*std::max_element(areas.begin(), areas.end()) > 0.0))
    throw SceneError(light.label + ": the object has no area to emit from: its triangles are too thin for float");
  const AliasTable alias = buildAliasTable(quantizeCdf(areas));
  double area = 0.0;
  for (double a : areas) area += a;
  const uint32_t header[] = {uint32_t(primitives.size()), alias.bits, light.surface->twoSided ? 1u : 0u,
                             std::bit_cast<uint32_t>(float(area))};
  record.dataFirst = data.append(std::span<const uint32_t>(header));
  appendAliasColumns(alias, data);
  for (const device::Primitive& p : primitives) {
    const uint32_t words[device::kPrimitiveWords] = {
        std::bit_cast<uint32_t>(p.a.x), std::bit_cast<uint32_t>(p.a.y), std::bit_cast<uint32_t>(p.a.z), p.type,
        std::bit_cast<uint32_t>(p.b.x), std::bit_cast<uint32_t>(p.b.y), std::bit_cast<uint32_t>(p.b.z), p.material,
        std::bit_cast<uint32_t>(p.c.x), std::bit_cast<uint32_t>(p.c.y), std::bit_cast<uint32_t>(p.c.z), 0u};
    data.append(std::span<const uint32_t>(words));
  }
  record.dataWords = uint32_t(data.words().size()) - record.dataFirst;
}

// The corners of the surface's world box, in the camera frame: the light's
// frame is the world's axes about the box's centre (position the centre,
// direction world z, u axis world x).
LightReach reach(const Light& light, const LightFrame& frame) {
  const glm::dvec3 half = 0.5 * (light.surface->boundsHi - light.surface->boundsLo);
  LightReach out;
  out.centre = frame.position;
  out.axis = frame.axis;
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0})
      for (double sz : {-1.0, 1.0})
        out.corners.push_back(frame.position + frame.tangent * (sx * half.x) + frame.bitangent * (sy * half.y) +
                              frame.axis * (sz * half.z));
  return out;
}

std::string unreachableBecause(const Light& light, const LightFrame& frame, const Camera& camera) {
  double highest = frame.position.z;
  for (const glm::dvec3& corner : reach(light, frame).corners) highest = std::max(highest, corner.z);
  return behindPlaneBecause(highest, camera);
}

// Not aimed: the surface's beams are drawn as it emits them.
double aim(const Light&, const LightFrame&, const AimTarget&, device::LightRecord&) { return 1.0; }

}  // namespace

const LightTypeUnit& objectLightUnit() {
  static const LightTypeUnit unit{
      .type = LightType::Object,
      .name = "object",
      .keys = {"two_sided"},
      .positionKey = nullptr,
      .directionKey = nullptr,
      .tangentFromUAxis = true,
      .aimedWeightsVary = false,
      .onObject = true,
      .parse = parse,
      .validate = validate,
      .pack = pack,
      .unreachableBecause = unreachableBecause,
      .aim = aim,
      .reach = reach,
  };
  return unit;
}

}  // namespace spectrace
