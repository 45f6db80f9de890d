// A lens system: real surfaces traced beam by beam at each beam's own
// wavelength (shaders/cameras/lens_system.h is its kernel). The scene's
// "camera.lens" lists the surfaces from the object side to the sensor, or
// names a file holding them: a JSON lens file, or pbrt-v4's lens table
// (.dat). A beam that reflects, is totally reflected, or misses a surface's
// semi-aperture or the barrel's front opening is absorbed, so vignetting
// and chromatic aberration are traced, not modelled. Camera connections
// end on the barrel's front opening (a disk every entering beam crosses)
// and trace the lens from there; no camera paths start.
#include "camera/lens_system_camera.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camera/camera_types.h"
#include "camera/entrance_disk_model.h"
#include "camera/world_limits.h"
#include "device_shared.h"
#include "json/input_file.h"
#include "spectrum/glass.h"

namespace spectrace {
namespace {

namespace jf = json_fields;

// Surfaces a lens may have: more than any photographic lens (about 30).
constexpr size_t kMaxLensSurfaces = 64;

// A lens file is text of a few kilobytes.
constexpr uint64_t kMaxLensFileBytes = uint64_t(1) << 20;

// Whether the lens comes from a pbrt table (.dat), whose messages point at
// lines and columns, not JSON pointers.
bool isTable(const LensSystem& lens) { return lens.file.extension() == ".dat"; }

class LensSystemModel final : public EntranceDiskModel {
 public:
  explicit LensSystemModel(LensSystem lens)
      : EntranceDiskModel(lens.prescription.frontZ(), lens.prescription.surfaces.front().semiApertureM, 1.0, "lens"),
        lens_(std::move(lens)) {}
  const LensSystem& lens() const { return lens_; }

  // Every length and the geometry were checked as they were read (they
  // name their file); what is left needs the scene's spectrum: each glass
  // must have a real index >= 1 and no pole over it.
  void validate(const CameraFieldCheck& check) const override {
    const auto& surfaces = lens_.prescription.surfaces;
    for (size_t i = 0; i < surfaces.size(); ++i) {
      const LensMedium& m = surfaces[i].medium;
      if (m.isAir()) continue;
      const std::string problem =
          sellmeierRangeProblem(m.b, m.cUm2, m.label, check.spectrumMinNm(), check.spectrumMaxNm());
      if (!problem.empty()) failAt(i, "medium", problem);
    }
  }

  // cameraParams: the front opening's radius squared, the body's half
  // width and height (the barrel may be wider than the sensor), whether an
  // index depends on the wavelength. The surface table follows the kernel's
  // layout (shaders/cameras/lens_system.h).
  void pack(device::TraceConstants& c, SceneData& data) const override {
    const LensPrescription& p = lens_.prescription;
    c.cameraType = device::kCameraLensSystem;
    c.cameraFrontZ = float(frontZ());
    const double widest = p.widestSemiApertureM();
    c.cameraParams = glm::vec4(float(radiusM() * radiusM()), std::max(c.sensorHalfSize.x, float(widest)),
                               std::max(c.sensorHalfSize.y, float(widest)), p.disperses() ? 1.0f : 0.0f);
    const std::vector<double> z = p.vertexZ();
    std::vector<float> table;
    for (size_t i = 0; i < p.surfaces.size(); ++i) {
      const LensSurface& s = p.surfaces[i];
      const double curvature = s.radiusM == 0.0 ? 0.0 : 1.0 / s.radiusM;
      table.insert(table.end(), {float(z[i]), float(curvature), float(s.semiApertureM * s.semiApertureM)});
      for (double b : s.medium.b) table.push_back(float(b));
      for (double cc : s.medium.cUm2) table.push_back(float(cc));
    }
    const uint32_t count = uint32_t(p.surfaces.size());
    c.cameraDataFirst = data.append(std::span<const uint32_t>(&count, 1));
    data.append(std::span<const float>(table));
  }
  const char* frontName() const override { return "the lens's front opening"; }
  // No bound: aberrations put a light's image anywhere the trace takes it.
  std::optional<SensorBox> reachOnSensor(const EmitterReach&) const override { return std::nullopt; }
  std::optional<double> cameraPathEntranceAreaM2() const override { return std::nullopt; }
  std::string cameraPathsAbsentBecause() const override {
    return "a lens system starts no camera paths (light paths and their camera connections trace it)";
  }
  std::vector<std::filesystem::path> files() const override {
    if (lens_.file.empty()) return {};
    return {lens_.file};
  }

 private:
  [[noreturn]] void failAt(size_t surface, const char* key, const std::string& what) const {
    lens_.source.fail(lens_.fieldOf(surface, key), what);
  }
  LensSystem lens_;
};

// "air", a catalogue glass's name, or {"nd": n, "vd": v} (a model glass).
LensMedium parseMedium(const jf::Source& c, const jf::Json& v, const std::string& ptr) {
  LensMedium m;
  if (v.is_string()) {
    const std::string name = v.get<std::string>();
    if (name == "air") return m;
    const SellmeierGlass* glass = glassNamed(name);
    if (!glass) {
      std::vector<std::string> names = glassNames();
      names.insert(names.begin(), "air");
      const jf::Keys keys(names.begin(), names.end());
      c.fail(ptr, fmt::format("unknown medium {}{} (known: {}, or {{\"nd\": n, \"vd\": v}} for a model glass)",
                              jf::jsonQuoted(name), jf::suggestion(name, keys), jf::joinKeys(keys)));
    }
    m.label = glass->name;
    m.b = glass->b;
    m.cUm2 = glass->cUm2;
    return m;
  }
  if (!v.is_object())
    c.fail(ptr, fmt::format("must be \"air\", a glass name or {{\"nd\": n, \"vd\": v}} (got {})", jf::describe(v)));
  jf::checkObject(c, v, ptr, {"nd", "vd"}, "a model glass");
  const double nd = jf::getNumber(c, jf::require(c, v, ptr, "nd"), jf::child(ptr, "nd"));
  const double vd = jf::getPositive(c, jf::require(c, v, ptr, "vd"), jf::child(ptr, "vd"));
  if (!(nd >= 1.0))
    c.fail(jf::child(ptr, "nd"),
           fmt::format("an index below 1 (got {}): no glass is faster than vacuum", jf::fmtNum(nd)));
  if (nd == 1.0) return m;
  const auto glass = modelGlass(nd, vd);
  if (!glass) c.fail(ptr, "no model glass has this nd and vd");
  m.label = fmt::format("nd {}, vd {}", jf::fmtNum(nd), jf::fmtNum(vd));
  m.b = glass->b;
  m.cUm2 = glass->cUm2;
  return m;
}

LensSurface parseSurface(const jf::Source& c, const jf::Json& v, const std::string& ptr, bool last, bool focusGiven) {
  jf::checkObject(c, v, ptr, {"radius_m", "thickness_m", "semi_aperture_m", "medium", "stop"}, "a lens surface");
  LensSurface s;
  s.radiusM =
      jf::getNumber(c, jf::require(c, v, ptr, "radius_m", " (0 for a flat surface)"), jf::child(ptr, "radius_m"));
  if (!(std::abs(s.radiusM) <= kMaxCoordinateM))
    c.fail(jf::child(ptr, "radius_m"), fmt::format("must be at most {:g} m in magnitude", kMaxCoordinateM));
  if (const jf::Json* t = jf::find(v, "thickness_m")) {
    s.thicknessM = jf::getNonNegative(c, *t, jf::child(ptr, "thickness_m"));
    if (!(s.thicknessM <= kMaxCoordinateM))
      c.fail(jf::child(ptr, "thickness_m"), fmt::format("must be at most {:g} m", kMaxCoordinateM));
  } else if (!(last && focusGiven)) {
    jf::require(c, v, ptr, "thickness_m", last ? " (to the sensor, unless focus_distance_m solves it)" : "");
  }
  s.semiApertureM = jf::getLength(c, jf::require(c, v, ptr, "semi_aperture_m"), jf::child(ptr, "semi_aperture_m"),
                                  kMaxCoordinateM);
  if (const jf::Json* m = jf::find(v, "medium")) s.medium = parseMedium(c, *m, jf::child(ptr, "medium"));
  if (const jf::Json* stop = jf::find(v, "stop")) {
    if (!stop->is_boolean())
      c.fail(jf::child(ptr, "stop"), fmt::format("must be true or false (got {})", jf::describe(*stop)));
    s.stop = stop->get<bool>();
  }
  return s;
}

// pbrt-v4's lens table (cameras.cpp, RealisticCamera): one surface a line,
// object side first, of four numbers in millimetres: curvature radius
// (0: the aperture stop), thickness, the index behind the surface (0: air)
// and aperture diameter. '#' starts a comment. The index is one number for
// every wavelength, so such a lens does not disperse.
std::vector<LensSurface> parsePbrtTable(const jf::Source& c, const std::string& text, std::vector<int>& lineOf) {
  std::vector<LensSurface> surfaces;
  std::istringstream lines(text);
  std::string line;
  for (int lineNo = 1; std::getline(lines, line); ++lineNo) {
    line = line.substr(0, line.find('#'));
    std::istringstream fields(line);
    std::vector<double> row;
    std::string token;
    while (fields >> token) {
      size_t used = 0;
      double x = 0.0;
      try {
        x = std::stod(token, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != token.size() || !std::isfinite(x))
        c.fail(fmt::format("line {}", lineNo), fmt::format("{} is not a finite number", jf::jsonQuoted(token)));
      row.push_back(x);
    }
    if (row.empty()) continue;
    const std::string where = fmt::format("line {}", lineNo);
    if (row.size() != 4)
      c.fail(where, fmt::format("has {} numbers; a surface is 4: curvature radius, thickness, index (0: air) and "
                                "aperture diameter, in mm",
                                row.size()));
    LensSurface s;
    s.radiusM = row[0] * 1e-3;
    s.thicknessM = row[1] * 1e-3;
    s.semiApertureM = row[3] * 0.5e-3;
    s.stop = row[0] == 0.0;
    if (!(row[1] >= 0.0)) c.fail(where, fmt::format("the thickness must be >= 0 mm (got {})", jf::fmtNum(row[1])));
    if (!(row[3] > 0.0))
      c.fail(where, fmt::format("the aperture diameter must be > 0 mm (got {})", jf::fmtNum(row[3])));
    if (row[2] != 0.0 && !(row[2] >= 1.0))
      c.fail(where, fmt::format("an index below 1 (got {}): no glass is faster than vacuum (0 means air)",
                                jf::fmtNum(row[2])));
    if (row[2] > 1.0) {
      s.medium.label = "index " + jf::fmtNum(row[2]);
      s.medium.b = {row[2] * row[2] - 1.0, 0.0, 0.0};
    }
    surfaces.push_back(s);
    lineOf.push_back(lineNo);
  }
  return surfaces;
}

// Exactly one stop, flat; every semi-aperture within its sphere; no two
// neighbouring surfaces, nor the last and the sensor, crossing inside
// their common aperture; air before the sensor.
void checkGeometry(const LensSystem& where, const LensPrescription& lens) {
  const jf::Source& c = where.source;
  const auto& s = lens.surfaces;
  const auto at = [&](size_t i, const char* key) { return where.fieldOf(i, key); };
  const std::string surfacesField = where.surfacesField();
  if (s.empty()) c.fail(surfacesField, "a lens needs at least one surface");
  if (s.size() > kMaxLensSurfaces)
    c.fail(surfacesField, fmt::format("has {} surfaces; a lens has at most {}", s.size(), kMaxLensSurfaces));
  std::vector<size_t> stops;
  for (size_t i = 0; i < s.size(); ++i)
    if (s[i].stop) stops.push_back(i);
  if (stops.empty())
    c.fail(surfacesField, "no surface is the aperture stop: " + where.howToMarkTheStop());
  if (stops.size() > 1)
    c.fail(at(stops[1], "stop"), fmt::format("a second aperture stop (surface {} is one already); a lens has one",
                                             stops[0]));
  if (s[stops[0]].radiusM != 0.0)
    c.fail(at(stops[0], "radius_m"), fmt::format("the aperture stop must be flat (radius_m 0, got {})",
                                                 jf::fmtNum(s[stops[0]].radiusM)));
  for (size_t i = 0; i < s.size(); ++i)
    if (s[i].radiusM != 0.0 && s[i].semiApertureM > std::abs(s[i].radiusM))
      c.fail(at(i, "semi_aperture_m"),
             fmt::format("{} m is larger than the surface's sphere allows (its radius is {} m)",
                         jf::fmtNum(s[i].semiApertureM), jf::fmtNum(std::abs(s[i].radiusM))));
  if (!s.back().medium.isAir())
    c.fail(at(s.size() - 1, "medium"), fmt::format("must be air: the sensor sits in air behind the last surface "
                                                   "(got {})",
                                                   s.back().medium.label));
  // z(r) of surface i is its vertex's z minus its sag; sampled finely over
  // the common aperture (each sag is monotone in r, their difference
  // nearly so).
  constexpr int kSteps = 256;
  for (size_t i = 0; i < s.size(); ++i) {
    const bool last = i + 1 == s.size();
    const double reach = last ? s[i].semiApertureM : std::min(s[i].semiApertureM, s[i + 1].semiApertureM);
    for (int k = 0; k <= kSteps; ++k) {
      const double r = reach * k / kSteps;
      const double gap = s[i].thicknessM - s[i].sagAt(r) + (last ? 0.0 : s[i + 1].sagAt(r));
      if (gap < 0.0 || (last && gap <= 0.0))
        c.fail(at(i, "thickness_m"),
               last ? fmt::format("the last surface reaches the sensor {} m from the axis (thickness {} m; "
                                  "focus_distance_m solves it)",
                                  jf::fmtNum(r), jf::fmtNum(s[i].thicknessM))
                    : fmt::format("surfaces {} and {} cross {} m from the axis (thickness {} m)", i, i + 1,
                                  jf::fmtNum(r), jf::fmtNum(s[i].thicknessM)));
    }
  }
}

// Solves the last thickness for `focusDistanceM` (from the sensor) at the
// d line, then checks the geometry with it.
void focus(const jf::Source& c, const std::string& focusPtr, LensPrescription& lens, double focusDistanceM) {
  const auto back = focusedBackThicknessM(lens, focusDistanceM, kLineDNm);
  if (!back) {
    const auto cardinal = paraxialCardinal(lens, kLineDNm);
    c.fail(focusPtr,
           cardinal && cardinal->focalLengthM > 0.0
               ? fmt::format("cannot be focused: an object {} m from the sensor is too near for this lens (focal "
                             "length {} m; object and image are at least four focal lengths apart)",
                             jf::fmtNum(focusDistanceM), jf::fmtNum(cardinal->focalLengthM))
               : std::string("cannot be focused: the lens forms no real image (it does not converge light)"));
  }
  lens.surfaces.back().thicknessM = *back;
}

// Narrows the stop to f-number `n` (paraxial, at the d line, for an object
// at infinity); a lens opens no wider than its own stop allows.
void stopDown(const jf::Source& c, const std::string& ptr, LensPrescription& lens, double n) {
  const auto widest = fNumber(lens, kLineDNm);
  if (!widest) c.fail(ptr, "the lens forms no real image, so it has no f-number");
  if (n < *widest)
    c.fail(ptr, fmt::format("f/{} is wider than the lens opens: its stop allows f/{} at the widest", jf::fmtNum(n),
                            jf::fmtNum(std::round(*widest * 1000.0) / 1000.0)));
  // The f-number is inversely proportional to the stop's semi-aperture.
  for (LensSurface& s : lens.surfaces)
    if (s.stop) s.semiApertureM *= *widest / n;
}

LensSystem parseLens(const jf::Source& scene, const jf::Json& v, const std::string& ptr) {
  jf::checkObject(scene, v, ptr, {"surfaces", "file", "focus_distance_m", "f_number"}, "camera.lens");
  LensSystem lens;
  std::optional<double> focusDistance;
  if (const jf::Json* f = jf::find(v, "focus_distance_m"))
    focusDistance = jf::getLength(scene, *f, jf::child(ptr, "focus_distance_m"), kMaxCoordinateM);
  const jf::Json* file = jf::find(v, "file");
  const jf::Json* inlineSurfaces = jf::find(v, "surfaces");
  if (file && inlineSurfaces) scene.fail(ptr, "has both \"surfaces\" and \"file\"; give one");
  if (!file && !inlineSurfaces) scene.fail(ptr, "needs \"surfaces\" (a list, object side first) or \"file\"");
  jf::Json fileRoot;
  const jf::Json* surfaces = inlineSurfaces;
  lens.source = scene;
  lens.surfacesPtr = jf::child(ptr, "surfaces");
  if (file) {
    const std::string name = jf::getString(scene, *file, jf::child(ptr, "file"));
    lens.file = scene.resolve(name);
    std::string text;
    try {
      text = readInputFile(lens.file, "lens file", kMaxLensFileBytes);
    } catch (const InputFileError& e) {
      scene.fail(jf::child(ptr, "file"), e.what());
    }
    lens.source.file = lens.file.string();
    lens.source.dir = lens.file.parent_path();
    if (isTable(lens)) {
      lens.prescription.surfaces = parsePbrtTable(lens.source, text, lens.tableLines);
      lens.surfacesPtr = "";
    } else {
      fileRoot = jf::parseJson(lens.source, text);
      jf::checkObject(lens.source, fileRoot, "", {"name", "source", "surfaces", "focus_distance_m"}, "a lens file");
      surfaces = &jf::require(lens.source, fileRoot, "", "surfaces");
      lens.surfacesPtr = "/surfaces";
      if (const jf::Json* f = jf::find(fileRoot, "focus_distance_m"); f && !focusDistance)
        focusDistance = jf::getLength(lens.source, *f, "/focus_distance_m", kMaxCoordinateM);
    }
  }
  if (surfaces) {
    if (!surfaces->is_array() || surfaces->empty())
      lens.source.fail(lens.surfacesPtr, fmt::format("must be a non-empty array of surfaces, object side first "
                                                     "(got {})",
                                                     jf::describe(*surfaces)));
    for (size_t i = 0; i < surfaces->size() && i <= kMaxLensSurfaces; ++i)
      lens.prescription.surfaces.push_back(parseSurface(lens.source, (*surfaces)[i], jf::child(lens.surfacesPtr, i),
                                                        i + 1 == surfaces->size(), focusDistance.has_value()));
  }
  // Where the geometry's messages point: the scene's own field when the
  // surfaces are inline, else the lens file's.
  checkGeometry(lens, [&] {
    LensPrescription checked = lens.prescription;
    if (focusDistance && !checked.surfaces.empty()) checked.surfaces.back().thicknessM = 1.0;  // solved below
    return checked;
  }());
  if (focusDistance) {
    focus(scene, jf::child(ptr, "focus_distance_m"), lens.prescription, *focusDistance);
    checkGeometry(lens, lens.prescription);
  }
  if (const jf::Json* n = jf::find(v, "f_number")) {
    const std::string nPtr = jf::child(ptr, "f_number");
    stopDown(scene, nPtr, lens.prescription, jf::getPositive(scene, *n, nPtr));
  }
  lens.focusDistanceM = focusDistance;
  return lens;
}

std::shared_ptr<const CameraModel> parse(const jf::Source& c, const jf::Json& v, const std::string& ptr) {
  return lensSystemModel(parseLens(c, v, ptr));
}

}  // namespace

std::string LensSystem::surfacesField() const { return isTable(*this) ? "its surface lines" : surfacesPtr; }

std::string LensSystem::howToMarkTheStop() const {
  return isTable(*this) ? "give exactly one line a curvature radius of 0 (the stop is flat)"
                        : "mark exactly one flat surface \"stop\": true";
}

std::string LensSystem::fieldOf(size_t surface, const std::string& key) const {
  if (!isTable(*this)) return jf::child(jf::child(surfacesPtr, surface), key);
  // A pbrt table's columns, by the JSON key of the same quantity.
  const std::string column = key == "radius_m" || key == "stop" ? "curvature radius"
                             : key == "thickness_m"              ? "thickness"
                             : key == "semi_aperture_m"          ? "aperture diameter"
                                                                 : "index";
  return fmt::format("line {} ({})", surface < tableLines.size() ? tableLines[surface] : 0, column);
}

std::shared_ptr<const CameraModel> lensSystemModel(LensSystem lens) {
  return std::make_shared<LensSystemModel>(std::move(lens));
}

const LensSystem* lensSystemOf(const Camera& camera) {
  const auto* model = dynamic_cast<const LensSystemModel*>(camera.model.get());
  return model ? &model->lens() : nullptr;
}

const CameraTypeUnit& lensSystemCameraUnit() {
  static const CameraTypeUnit unit{"lens", parse};
  return unit;
}

}  // namespace spectrace
