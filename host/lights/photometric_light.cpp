// Photometric light: a luminaire's goniometric table (IES LM-63 or
// EULUMDAT, lights/photometric_file.h) from one point. `direction` is nadir
// (gamma = 0), by default straight down; `c0_axis` the direction of the
// C = 0 half-plane, by default the world X axis projected off nadir (world
// Z for a nadir along X). Its flux is the table's own (the integral of the
// bilinear table: the luminaire's output, which the file's rated lamp
// lumens exceed by its losses), unless power_lm or power_w sets it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "camera/world_limits.h"
#include "lights/light_shared.h"
#include "spectrum/alias_table.h"
#include "spectrum/wavelength_sampler.h"

namespace spectrace {

const LightTypeUnit& photometricLightUnit();  // below; the table is lights/light_types.cpp

namespace {

namespace jf = json_fields;
namespace fs = std::filesystem;

// The C = 0 direction: `c0` without its component along `nadir`, unit length;
// a zero vector when they are parallel.
glm::dvec3 projectedOff(const glm::dvec3& c0, const glm::dvec3& nadir) {
  const glm::dvec3 off = c0 - nadir * glm::dot(c0, nadir);
  const double length = glm::length(off);
  return length > 1e-9 ? off / length : glm::dvec3(0.0);
}

void parse(const jf::Source& c, const jf::Json& v, const std::string& ptr, Light& light) {
  light.position = jf::getPoint(c, jf::require(c, v, ptr, "position"), jf::child(ptr, "position"), kMaxCoordinateM);
  light.direction = {0.0, -1.0, 0.0};
  if (const jf::Json* d = jf::find(v, "direction")) light.direction = jf::getDirection(c, *d, jf::child(ptr, "direction"));
  if (const jf::Json* a = jf::find(v, "c0_axis")) {
    const std::string ap = jf::child(ptr, "c0_axis");
    light.uAxis = projectedOff(jf::getDirection(c, *a, ap), light.direction);
    if (light.uAxis == glm::dvec3(0.0)) c.fail(ap, "is parallel to the light's direction (nadir); it must point across it");
  } else {
    light.uAxis = projectedOff({1.0, 0.0, 0.0}, light.direction);
    if (light.uAxis == glm::dvec3(0.0)) light.uAxis = projectedOff({0.0, 0.0, 1.0}, light.direction);
  }
  const std::string fp = jf::child(ptr, "file");
  const std::string written =
      jf::getString(c, jf::require(c, v, ptr, "file", " (an IES LM-63 .ies or EULUMDAT .ldt file)"), fp);
  const fs::path path(written);
  const fs::path resolved = c.resolve(path);
  try {
    light.photometry = std::make_shared<const PhotometricTable>(readPhotometricFile(resolved));
  } catch (const PhotometricFileError& e) {
    c.fail(fp, e.what());
  }
  if (!(light.photometry->tableLumens() > 0.0))
    c.fail(fp, fmt::format("{}: the table emits nothing (every candela value is 0)", written));
  light.photometryFile = resolved;
}

void validate(const Light&, const LightFieldCheck&) {}

// The scene data (device_shared.h, kPhotometricHeaderWords). Angles in
// turns, intensities over the table's flux; each patch's envelope bounds
// I sin(gamma) above, with room for float rounding, and the tries follow
// from the least acceptance among the patches that can be drawn.
void pack(const Light& light, const CameraFrame&, device::LightRecord& record, SceneData& data) {
  const PhotometricTable& table = *light.photometry;
  const size_t nC = table.cDegrees.size(), nG = table.gammaDegrees.size();
  const double flux = table.tableLumens();
  constexpr double kRad = std::numbers::pi / 180.0;
  std::vector<float> cTurns, gTurns, intensity, envelope;
  for (double c : table.cDegrees) cTurns.push_back(float(c / 360.0));
  for (double g : table.gammaDegrees) gTurns.push_back(float(g / 360.0));
  for (double i : table.candela) intensity.push_back(float(i / flux));
  std::vector<double> weights;
  double leastAcceptance = 1.0;
  for (size_t c = 0; c + 1 < nC; ++c) {
    for (size_t g = 0; g + 1 < nG; ++g) {
      const double g0 = table.gammaDegrees[g] * kRad, g1 = table.gammaDegrees[g + 1] * kRad;
      const double sinMax = (g0 <= 0.5 * std::numbers::pi && g1 >= 0.5 * std::numbers::pi)
                                ? 1.0
                                : std::max(std::sin(g0), std::sin(g1));
      const size_t at = c * nG + g;
      const double corner = std::max({intensity[at], intensity[at + 1], intensity[at + nG], intensity[at + nG + 1]});
      // The kernel's sine (cosSin2Pi) is within 4e-7 of the true one, and the
      // bilinear value within an ulp or two of the largest corner. A patch
      // whose corners are below 1e-30 of the table's flux per steradian
      // (float values near underflow) is never drawn: it holds nothing a
      // render can show.
      const double bound = corner * (sinMax + 1e-6) * (1.0 + 1e-6);
      weights.push_back(corner > 1e-30 ? std::max(table.patchLumens(c, g), 0.0) : 0.0);
      envelope.push_back(bound > 0.0 ? floatAtLeast(bound) : 1.0f);
      if (weights.back() > 0.0) {
        const double area = (table.cDegrees[c + 1] - table.cDegrees[c]) * kRad * (g1 - g0);
        leastAcceptance = std::min(leastAcceptance, weights.back() / flux / (double(envelope.back()) * area));
      }
    }
  }
  // A patch's acceptance is its mean of I sin(gamma) over the envelope:
  // about 1/12 at worst (one lit corner at the pole, where sin(gamma)
  // vanishes), so some 500 tries; the envelope's slack lowers it only in a
  // patch at the pole narrower than the readers allow (0.001 degrees). The
  // tries bound the chance that a beam runs out of them by 2^-64.
  const double tries = std::ceil(64.0 * std::numbers::ln2 / -std::log1p(-std::min(leastAcceptance, 0.999999)));
  if (!(tries >= 1.0 && tries <= 4096.0))
    throw std::logic_error(fmt::format("{}: photometric patch acceptance {} needs {} tries", light.label,
                                       leastAcceptance, tries));
  const AliasTable alias = buildAliasTable(quantizeCdf(weights));
  const uint32_t header[] = {uint32_t(nC), uint32_t(nG), alias.bits, uint32_t(tries)};
  record.dataFirst = data.append(std::span<const uint32_t>(header));
  data.append(std::span<const float>(cTurns));
  data.append(std::span<const float>(gTurns));
  data.append(std::span<const float>(intensity));
  data.append(std::span<const float>(envelope));
  appendAliasColumns(alias, data);
  record.dataWords = uint32_t(data.words().size()) - record.dataFirst;
}

std::string unreachableBecause(const Light&, const LightFrame& frame, const Camera& camera) {
  return behindPlaneBecause(frame.position.z + 0.0, camera);
}

// Not aimed: the table's directions are drawn as the file gives them.
double aim(const Light&, const LightFrame&, const AimTarget&, device::LightRecord&) { return 1.0; }

LightReach reach(const Light&, const LightFrame& frame) { return flatReach(frame, 0.0, 0.0); }

}  // namespace

const LightTypeUnit& photometricLightUnit() {
  static const LightTypeUnit unit{
      .type = LightType::Photometric,
      .name = "photometric",
      .keys = {"file", "position", "direction", "c0_axis"},
      .positionKey = "position",
      .directionKey = "direction",
      .tangentFromUAxis = true,
      .aimedWeightsVary = false,
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
