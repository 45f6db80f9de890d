// Scene files: JSON, validated field by field. Every problem becomes a
// SceneError "<file>: <json pointer>: <what is wrong>"; nothing reaches the
// renderer unchecked (no NaN, no zero-length axes, no silently ignored keys).
//
// Format summary (all lengths in metres, powers in watts, wavelengths in nm;
// // and /* */ comments are tolerated):
//   spectrum  {min_nm, max_nm, bins}                       optional
//   observer  "CIE1931_2" | "CIE1964_10"                   optional
//   camera    {position, look_at, up, sensor{width_m, height_m, pixels},
//              pinhole{distance_m, radius_m}, exposure_s}  required
//   lights    [ {type, name, power_w, spd, ...type fields} ] required, non-empty
//   render    {beams, seed}                                optional
#include "scene/scene.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <unordered_set>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <openssl/evp.h>

namespace spectrace {

const char* lightTypeName(LightType type) {
  switch (type) {
    case LightType::Point: return "point";
    case LightType::Spot: return "spot";
    case LightType::Disk: return "disk";
    case LightType::Rect: return "rect";
    case LightType::Laser: return "laser";
  }
  return "unknown";
}

std::string sceneSha256Hex(std::string_view bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha256(), nullptr) != 1)
    throw SceneError("SHA-256 computation failed (OpenSSL EVP_Digest)");
  static const char* hex = "0123456789abcdef";
  std::string out;
  out.reserve(2 * length);
  for (unsigned int i = 0; i < length; ++i) {
    out.push_back(hex[digest[i] >> 4]);
    out.push_back(hex[digest[i] & 15]);
  }
  return out;
}

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using Keys = std::vector<std::string_view>;

std::string fmtNum(double x) { return fmt::format("{}", x); }

constexpr int kMaxPixelsPerAxis = 65535;
constexpr int64_t kMaxPixelsTotal = int64_t(1) << 28;
constexpr int kMaxBins = 100000;
constexpr double kMaxWavelengthNm = 100000.0;  // 0.1 mm; keeps spectral tables finite
constexpr double kMaxKelvin = 1e6;  // hotter than any star; keeps Planck's law finite
// Bound on coordinates and lengths (metres): far beyond any sensible scene,
// far inside float range, so the single-precision device math stays finite.
constexpr double kMaxCoordinateM = 1e12;
// |cross(view, up)| of the unit vectors below this: up is collinear with view.
constexpr double kCollinearEps = 1e-9;

// ---------------------------------------------------------------------------
// JSON pointers and messages

std::string escapeToken(std::string_view key) {
  std::string out;
  for (char ch : key) {
    if (ch == '~') out += "~0";
    else if (ch == '/') out += "~1";
    else out += ch;
  }
  return out;
}
std::string child(const std::string& ptr, std::string_view key) { return ptr + "/" + escapeToken(key); }
std::string child(const std::string& ptr, size_t index) { return ptr + "/" + std::to_string(index); }

std::string jsonQuoted(std::string_view s) { return json(std::string(s)).dump(); }

std::string joinKeys(const Keys& keys) {
  std::string out;
  for (auto k : keys) {
    if (!out.empty()) out += ", ";
    out += k;
  }
  return out;
}

// A short description of a JSON value for "(got ...)".
std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return v.dump();
    case json::value_t::string: {
      std::string s = v.get<std::string>();
      if (s.size() <= 48) return jsonQuoted(s);
      size_t cut = 45;
      while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;  // UTF-8 boundary
      return jsonQuoted(s.substr(0, cut)) + "...";
    }
    case json::value_t::array: {
      bool small = v.size() <= 4 && std::all_of(v.begin(), v.end(), [](const json& e) { return e.is_primitive(); });
      if (small) {
        std::string out = "[";
        for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + describe(v[i]);
        return out + "]";
      }
      return fmt::format("an array of {} element{}", v.size(), v.size() == 1 ? "" : "s");
    }
    case json::value_t::object: return "an object";
    default: return v.type_name();
  }
}

size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t up = row[j];
      size_t sub = diag + (std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                                   std::tolower(static_cast<unsigned char>(b[j - 1]))
                               ? 0
                               : 1);
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, sub});
      diag = up;
    }
  }
  return row[b.size()];
}

// "; did you mean "x"?" when one candidate is close to `word`.
std::string suggestion(std::string_view word, const std::vector<std::string_view>& candidates) {
  std::string_view best;
  size_t bestDistance = std::numeric_limits<size_t>::max();
  for (auto c : candidates) {
    size_t d = editDistance(word, c);
    if (d < bestDistance) {
      bestDistance = d;
      best = c;
    }
  }
  size_t limit = word.size() <= 3 ? 1 : word.size() <= 6 ? 2 : 3;
  if (best.empty() || bestDistance > limit) return "";
  return fmt::format("; did you mean {}?", jsonQuoted(best));
}

struct Ctx {
  std::string file;  // as shown in messages
  fs::path dir;      // folder relative CSV paths resolve against
  std::string note;  // appended to messages, e.g. ` (light "desk lamp")`

  [[noreturn]] void fail(const std::string& ptr, const std::string& what) const {
    // The root's pointer is "", shown as "/" so the message stays readable.
    throw SceneError(fmt::format("{}: {}: {}{}", file, ptr.empty() ? "/" : ptr, what, note));
  }
};

// ---------------------------------------------------------------------------
// Parsing, with duplicate keys rejected (nlohmann would keep the last).

struct DuplicateKey {
  std::string ptr;
  std::string key;
};

json parseJson(const Ctx& c, const std::string& text) {
  struct Frame {
    bool isArray;
    size_t next = 0;
    std::string ptr;
    std::string key;
    std::unordered_set<std::string> keys;
  };
  std::vector<Frame> stack;
  auto beginChild = [&](bool isArray) {
    std::string ptr;
    if (!stack.empty()) {
      Frame& parent = stack.back();
      ptr = parent.isArray ? child(parent.ptr, parent.next++) : child(parent.ptr, parent.key);
    }
    stack.push_back(Frame{isArray, 0, std::move(ptr), {}, {}});
  };
  json::parser_callback_t callback = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: beginChild(false); break;
      case json::parse_event_t::array_start: beginChild(true); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!stack.empty()) stack.pop_back();
        break;
      case json::parse_event_t::key: {
        if (stack.empty()) break;
        Frame& f = stack.back();
        std::string key = parsed.get<std::string>();
        if (!f.keys.insert(key).second) throw DuplicateKey{child(f.ptr, key), key};
        f.key = std::move(key);
        break;
      }
      case json::parse_event_t::value:
        if (!stack.empty() && stack.back().isArray) ++stack.back().next;
        break;
    }
    return true;
  };
  try {
    return json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const DuplicateKey& d) {
    c.fail(d.ptr, fmt::format("duplicate key {} (each key may appear only once per object)", jsonQuoted(d.key)));
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    if (auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    c.fail("", fmt::format("invalid JSON: {} (byte {})", what, e.byte));
  } catch (const json::exception& e) {
    std::string what = e.what();
    if (auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    c.fail("", fmt::format("invalid JSON: {}", what));
  }
}

// ---------------------------------------------------------------------------
// Typed field access

const json* find(const json& obj, const std::string& key) {
  auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

const json& require(const Ctx& c, const json& obj, const std::string& ptr, const std::string& key,
                    std::string_view hint = {}) {
  const json* v = find(obj, key);
  if (!v) c.fail(child(ptr, key), fmt::format("missing required field {}{}", jsonQuoted(key), hint));
  return *v;
}

// Checks that `v` is an object whose keys are all in `allowed`.
void checkObject(const Ctx& c, const json& v, const std::string& ptr, const Keys& allowed, std::string_view what) {
  if (!v.is_object()) c.fail(ptr, fmt::format("{} must be an object (got {})", what, describe(v)));
  for (const auto& [key, value] : v.items()) {
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      c.fail(child(ptr, key), fmt::format("unknown key {} in {}{} (allowed keys: {})", jsonQuoted(key), what,
                                          suggestion(key, allowed), joinKeys(allowed)));
  }
}

double getNumber(const Ctx& c, const json& v, const std::string& ptr) {
  if (!v.is_number()) c.fail(ptr, fmt::format("must be a finite number (got {})", describe(v)));
  double d = v.get<double>();
  if (!std::isfinite(d)) c.fail(ptr, fmt::format("must be a finite number (got {})", describe(v)));
  return d;
}

double getPositive(const Ctx& c, const json& v, const std::string& ptr) {
  if (!v.is_number() || !std::isfinite(v.get<double>()) || !(v.get<double>() > 0.0))
    c.fail(ptr, fmt::format("must be a finite number > 0 (got {})", describe(v)));
  return v.get<double>();
}

// A length in metres: > 0 and at most kMaxCoordinateM.
double getLength(const Ctx& c, const json& v, const std::string& ptr) {
  double d = getPositive(c, v, ptr);
  if (d > kMaxCoordinateM)
    c.fail(ptr, fmt::format("must be a length in metres, > 0 and <= {:g} (got {})", kMaxCoordinateM, describe(v)));
  return d;
}

double getNonNegative(const Ctx& c, const json& v, const std::string& ptr) {
  if (!v.is_number() || !std::isfinite(v.get<double>()) || !(v.get<double>() >= 0.0))
    c.fail(ptr, fmt::format("must be a finite number >= 0 (got {})", describe(v)));
  return v.get<double>() == 0.0 ? 0.0 : v.get<double>();  // no -0
}

// An integer in [lo, hi]; integral floats such as 1e8 are accepted.
int64_t getInt(const Ctx& c, const json& v, const std::string& ptr, int64_t lo, int64_t hi) {
  auto bad = [&] { c.fail(ptr, fmt::format("must be an integer in {}..{} (got {})", lo, hi, describe(v))); };
  if (v.is_number_unsigned()) {
    uint64_t u = v.get<uint64_t>();
    if (u > static_cast<uint64_t>(hi) || static_cast<int64_t>(u) < lo) bad();
    return static_cast<int64_t>(u);
  }
  if (v.is_number_integer()) {
    int64_t i = v.get<int64_t>();
    if (i < lo || i > hi) bad();
    return i;
  }
  if (v.is_number_float()) {
    double d = v.get<double>();
    if (!std::isfinite(d) || std::floor(d) != d || d < static_cast<double>(lo) || d > static_cast<double>(hi)) bad();
    return static_cast<int64_t>(d);
  }
  bad();
  return 0;
}

// An unsigned 64-bit integer >= lo; integral floats below 2^64 are accepted.
uint64_t getU64(const Ctx& c, const json& v, const std::string& ptr, uint64_t lo) {
  auto bad = [&] {
    c.fail(ptr, fmt::format("must be an integer in {}..{} (got {})", lo, std::numeric_limits<uint64_t>::max(),
                            describe(v)));
  };
  uint64_t u = 0;
  if (v.is_number_unsigned()) {
    u = v.get<uint64_t>();
  } else if (v.is_number_integer()) {
    int64_t i = v.get<int64_t>();
    if (i < 0) bad();
    u = static_cast<uint64_t>(i);
  } else if (v.is_number_float()) {
    double d = v.get<double>();
    if (!std::isfinite(d) || std::floor(d) != d || d < 0.0 || d >= 18446744073709551616.0) bad();
    u = static_cast<uint64_t>(d);
  } else {
    bad();
  }
  if (u < lo) bad();
  return u;
}

std::string getString(const Ctx& c, const json& v, const std::string& ptr, bool allowEmpty = false) {
  if (!v.is_string()) c.fail(ptr, fmt::format("must be a string (got {})", describe(v)));
  std::string s = v.get<std::string>();
  if (s.empty() && !allowEmpty) c.fail(ptr, "must be a non-empty string");
  return s;
}

// [x, y, z]; with `limit`, every |component| must be <= limit.
glm::dvec3 getVec3(const Ctx& c, const json& v, const std::string& ptr,
                   double limit = std::numeric_limits<double>::infinity()) {
  if (!v.is_array() || v.size() != 3)
    c.fail(ptr, fmt::format("must be an array of 3 finite numbers [x, y, z] (got {})", describe(v)));
  glm::dvec3 out;
  for (int i = 0; i < 3; ++i) {
    std::string ip = child(ptr, size_t(i));
    out[i] = getNumber(c, v[size_t(i)], ip);
    if (std::abs(out[i]) > limit)
      c.fail(ip, fmt::format("must be a coordinate with magnitude <= {:g} m (got {})", limit, describe(v[size_t(i)])));
  }
  return out;
}

// A position in metres.
glm::dvec3 getPoint(const Ctx& c, const json& v, const std::string& ptr) {
  return getVec3(c, v, ptr, kMaxCoordinateM);
}

// Unit vector, robust against huge and tiny components; nullopt for zero.
std::optional<glm::dvec3> safeNormalize(const glm::dvec3& v) {
  double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(m > 0.0) || !std::isfinite(m)) return std::nullopt;
  glm::dvec3 w = v / m;
  return w / glm::length(w);
}

glm::dvec3 getDirection(const Ctx& c, const json& v, const std::string& ptr) {
  glm::dvec3 d = getVec3(c, v, ptr);
  auto n = safeNormalize(d);
  if (!n) c.fail(ptr, fmt::format("must not be zero-length (got {})", describe(v)));
  return *n;
}

// Default tangent for an axis: normalize(cross(pick, axis)) with pick = world
// Y (0, 1, 0), or world X (1, 0, 0) when |axis.y| > 0.9 (nearly vertical
// axes), so the tangent is never degenerate. For a rect facing -z this gives
// u = (-1, 0, 0), for one facing +z u = (1, 0, 0).
glm::dvec3 defaultTangent(const glm::dvec3& axis) {
  glm::dvec3 pick = std::abs(axis.y) > 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  return glm::normalize(glm::cross(pick, axis));
}


// ---------------------------------------------------------------------------
// Sections

SpectrumRange parseSpectrum(const Ctx& c, const json& v, const std::string& p) {
  checkObject(c, v, p, {"min_nm", "max_nm", "bins"}, "spectrum");
  SpectrumRange s;
  if (auto* x = find(v, "min_nm")) s.minNm = getPositive(c, *x, child(p, "min_nm"));
  if (auto* x = find(v, "max_nm")) s.maxNm = getPositive(c, *x, child(p, "max_nm"));
  for (const char* key : {"min_nm", "max_nm"})
    if (auto* x = find(v, key); x && x->get<double>() > kMaxWavelengthNm)
      c.fail(child(p, key), fmt::format("must be at most {} nm (got {})", fmtNum(kMaxWavelengthNm), describe(*x)));
  if (auto* x = find(v, "bins")) s.bins = static_cast<int>(getInt(c, *x, child(p, "bins"), 1, kMaxBins));
  if (!(s.minNm < s.maxNm))
    c.fail(find(v, "max_nm") ? child(p, "max_nm") : child(p, "min_nm"),
           fmt::format("spectrum range is empty: min_nm ({} nm) must be less than max_nm ({} nm)", fmtNum(s.minNm),
                       fmtNum(s.maxNm)));
  return s;
}

Camera parseCamera(const Ctx& c, const json& v, const std::string& p) {
  checkObject(c, v, p, {"position", "look_at", "up", "sensor", "pinhole", "exposure_s"}, "camera");
  Camera cam;
  cam.position = getPoint(c, require(c, v, p, "position"), child(p, "position"));
  cam.lookAt = getPoint(c, require(c, v, p, "look_at"), child(p, "look_at"));
  if (auto* x = find(v, "up")) cam.up = getDirection(c, *x, child(p, "up"));

  glm::dvec3 diff = cam.lookAt - cam.position;
  auto view = safeNormalize(diff);
  if (!view)
    c.fail(child(p, "look_at"), fmt::format("must differ from the camera position {} (zero-length view direction)",
                                            describe(v.at("position"))));
  if (glm::length(glm::cross(*view, cam.up)) < kCollinearEps)
    c.fail(child(p, "up"), fmt::format("{} is parallel to the view direction (look_at - position); choose an up "
                                       "vector that is not collinear with it",
                                       describe(find(v, "up") ? v.at("up") : json::array({0, 1, 0}))));

  if (auto* s = find(v, "sensor")) {
    std::string sp = child(p, "sensor");
    checkObject(c, *s, sp, {"width_m", "height_m", "pixels"}, "camera.sensor");
    if (auto* x = find(*s, "width_m")) cam.sensorWidthM = getLength(c, *x, child(sp, "width_m"));
    if (auto* x = find(*s, "height_m")) cam.sensorHeightM = getLength(c, *x, child(sp, "height_m"));
    if (auto* x = find(*s, "pixels")) {
      std::string pp = child(sp, "pixels");
      if (!x->is_array() || x->size() != 2)
        c.fail(pp, fmt::format("must be an array of 2 positive integers [width, height] (got {})", describe(*x)));
      cam.pixelsX = static_cast<int>(getInt(c, (*x)[0], child(pp, size_t(0)), 1, kMaxPixelsPerAxis));
      cam.pixelsY = static_cast<int>(getInt(c, (*x)[1], child(pp, size_t(1)), 1, kMaxPixelsPerAxis));
      int64_t total = int64_t(cam.pixelsX) * cam.pixelsY;
      if (total > kMaxPixelsTotal)
        c.fail(pp, fmt::format("too many pixels: {} x {} = {} (at most {})", cam.pixelsX, cam.pixelsY, total,
                               kMaxPixelsTotal));
    }
  }
  if (auto* h = find(v, "pinhole")) {
    std::string hp = child(p, "pinhole");
    checkObject(c, *h, hp, {"distance_m", "radius_m"}, "camera.pinhole");
    Pinhole ph;
    ph.distanceM = getLength(c, require(c, *h, hp, "distance_m"), child(hp, "distance_m"));
    ph.radiusM = getLength(c, require(c, *h, hp, "radius_m"), child(hp, "radius_m"));
    cam.pinhole = ph;
  }
  if (auto* x = find(v, "exposure_s")) cam.exposureS = getPositive(c, *x, child(p, "exposure_s"));
  return cam;
}

// Wraps a call into spd.h: SpdError (and anything else it throws) becomes a
// SceneError at `ptr`.
template <class F>
Spd callSpd(const Ctx& c, const std::string& ptr, F&& f) {
  try {
    return f();
  } catch (const SpdError& e) {
    c.fail(ptr, e.what());
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    c.fail(ptr, fmt::format("cannot build the spectrum: {}", e.what()));
  }
}

std::vector<double> getNumberArray(const Ctx& c, const json& v, const std::string& ptr) {
  if (!v.is_array() || v.empty())
    c.fail(ptr, fmt::format("must be a non-empty array of finite numbers (got {})", describe(v)));
  std::vector<double> out;
  out.reserve(v.size());
  for (size_t i = 0; i < v.size(); ++i) out.push_back(getNumber(c, v[i], child(ptr, i)));
  return out;
}

void parseSpd(const Ctx& c, const json& v, const std::string& p, const SpectrumRange& range, Light& light) {
  static const Keys kForms = {"blackbody_k", "csv", "table", "lambda_nm", "line_nm"};
  static const char* kFormsHelp =
      "a CIE illuminant name such as \"D65\", or an object with one of: {\"blackbody_k\": K}, {\"csv\": \"file.csv\"}, "
      "{\"table\": [[nm, value], ...]}, {\"lambda_nm\": [...], \"value\": [...]}, {\"line_nm\": nm}";
  if (v.is_string()) {
    std::string name = v.get<std::string>();
    auto spd = callSpd(c, p, [&]() -> Spd {
      auto s = cieIlluminant(name);
      if (!s) {
        auto names = cieIlluminantNames();
        std::vector<std::string_view> views(names.begin(), names.end());
        std::string hint = suggestion(name, views);  // case-insensitive: "d65" suggests "D65"
        std::string list;
        for (auto& n : names) list += (list.empty() ? "" : ", ") + n;
        c.fail(p, fmt::format("unknown CIE illuminant {}{} (known: {})", jsonQuoted(name), hint, list));
      }
      return *s;
    });
    light.spd = std::move(spd);
    light.spdLabel = name;
  } else if (v.is_object()) {
    std::vector<std::string_view> present;
    for (auto f : kForms)
      if (find(v, std::string(f))) present.push_back(f);
    if (present.empty() && find(v, "value")) present.push_back("lambda_nm");
    if (present.empty()) {
      // Unknown keys first: {"blackbdy_k": ...} should name the typo.
      Keys all = {"blackbody_k", "csv", "column", "table", "lambda_nm", "value", "line_nm", "fwhm_nm"};
      checkObject(c, v, p, all, "spd");
      c.fail(p, fmt::format("must be {} (got an object with none of these)", kFormsHelp));
    }
    if (present.size() > 1)
      c.fail(p, fmt::format("ambiguous spectrum: has both {} and {}; use exactly one of {}", jsonQuoted(present[0]),
                            jsonQuoted(present[1]), joinKeys(kForms)));
    std::string_view form = present[0];
    if (form == "blackbody_k") {
      checkObject(c, v, p, {"blackbody_k"}, "a blackbody spd");
      std::string kp = child(p, "blackbody_k");
      double kelvin = getPositive(c, v.at("blackbody_k"), kp);
      if (kelvin > kMaxKelvin)
        c.fail(kp, fmt::format("must be a temperature in kelvin, > 0 and <= {:g} (got {})", kMaxKelvin,
                               describe(v.at("blackbody_k"))));
      light.spd = callSpd(c, kp, [&] { return makeBlackbodySpd(kelvin, range.minNm, range.maxNm); });
      light.spdLabel = fmt::format("blackbody {} K", fmtNum(kelvin));
    } else if (form == "csv") {
      checkObject(c, v, p, {"csv", "column"}, "a csv spd");
      std::string cp = child(p, "csv");
      std::string rel = getString(c, v.at("csv"), cp);
      std::optional<std::string> column;
      if (auto* x = find(v, "column")) column = getString(c, *x, child(p, "column"));
      fs::path path(rel);
      fs::path resolved = path.is_absolute() ? path : (c.dir / path).lexically_normal();
      std::error_code ec;
      if (!fs::exists(resolved, ec))
        c.fail(cp, fmt::format("SPD file not found: {}{}", jsonQuoted(rel),
                               path.is_absolute() ? std::string()
                                                  : fmt::format(" (looked for {}, relative to the scene file's folder)",
                                                                jsonQuoted(fs::absolute(resolved, ec).string()))));
      if (!fs::is_regular_file(resolved, ec)) c.fail(cp, fmt::format("{} is not a regular file", jsonQuoted(resolved.string())));
      light.spd = callSpd(c, cp, [&] { return loadCsvSpd(resolved, column); });
      light.spdLabel = "csv " + rel + (column ? " column " + *column : "");
    } else if (form == "table") {
      checkObject(c, v, p, {"table"}, "a table spd");
      std::string tp = child(p, "table");
      const json& t = v.at("table");
      if (!t.is_array() || t.empty())
        c.fail(tp, fmt::format("must be a non-empty array of [wavelength_nm, value] pairs (got {})", describe(t)));
      std::vector<double> lambda, value;
      for (size_t i = 0; i < t.size(); ++i) {
        std::string rp = child(tp, i);
        if (!t[i].is_array() || t[i].size() != 2)
          c.fail(rp, fmt::format("must be a [wavelength_nm, value] pair (got {})", describe(t[i])));
        lambda.push_back(getNumber(c, t[i][0], child(rp, size_t(0))));
        value.push_back(getNumber(c, t[i][1], child(rp, size_t(1))));
      }
      light.spd = callSpd(c, tp, [&] { return makeTabulatedSpd(lambda, value); });
      light.spdLabel = fmt::format("inline table ({} points)", t.size());
    } else if (form == "lambda_nm") {
      checkObject(c, v, p, {"lambda_nm", "value"}, "a tabulated spd");
      std::vector<double> lambda = getNumberArray(c, require(c, v, p, "lambda_nm"), child(p, "lambda_nm"));
      std::vector<double> value = getNumberArray(c, require(c, v, p, "value"), child(p, "value"));
      if (lambda.size() != value.size())
        c.fail(child(p, "value"), fmt::format("has {} entries but lambda_nm has {}; they must be the same length",
                                              value.size(), lambda.size()));
      size_t n = lambda.size();
      light.spd = callSpd(c, p, [&] { return makeTabulatedSpd(std::move(lambda), std::move(value)); });
      light.spdLabel = fmt::format("inline table ({} points)", n);
    } else {  // line_nm
      checkObject(c, v, p, {"line_nm", "fwhm_nm"}, "a line spd");
      double center = getPositive(c, v.at("line_nm"), child(p, "line_nm"));
      std::optional<double> fwhm;
      if (auto* x = find(v, "fwhm_nm")) fwhm = getPositive(c, *x, child(p, "fwhm_nm"));
      light.spd = callSpd(c, p, [&] { return makeLineSpd(center, fwhm); });
      light.spdLabel = fmt::format("line {} nm", fmtNum(center));
      if (fwhm) light.spdLabel += fmt::format(" (FWHM {} nm)", fmtNum(*fwhm));
    }
  } else {
    c.fail(p, fmt::format("must be {} (got {})", kFormsHelp, describe(v)));
  }

  // The spectrum must carry power, and some of it inside the simulated range.
  const Spd& s = light.spd;
  if (s.lambdaNm.empty() || !std::isfinite(s.fullIntegral) || !(s.fullIntegral > 0.0))
    c.fail(p, "the spectrum has no power (its integral is 0)");
  Spd inside = s.clipped(range.minNm, range.maxNm);
  if (inside.lambdaNm.empty() || !(inside.integral() > 0.0))
    c.fail(p, fmt::format("the spectrum ({}) emits nothing inside the scene's spectrum range {}-{} nm",
                          light.spdLabel, fmtNum(range.minNm), fmtNum(range.maxNm)));
}

Light parseLight(const Ctx& outer, const json& v, const std::string& p, const SpectrumRange& range) {
  Ctx c = outer;
  if (!v.is_object()) c.fail(p, fmt::format("a light must be an object (got {})", describe(v)));
  Light light;
  light.label = p;
  if (auto* n = find(v, "name")) {
    light.name = getString(c, *n, child(p, "name"));
    c.note = fmt::format(" (light {})", jsonQuoted(light.name));
  }
  static const Keys kTypes = {"point", "spot", "disk", "rect", "laser"};
  if (!find(v, "type"))  // name a typo such as "typ" before complaining that "type" is missing
    checkObject(c, v, p,
                {"type", "name", "power_w", "spd", "position", "direction", "cone_deg", "center", "normal",
                 "radius_m", "size_m", "u_axis", "origin"},
                "a light");
  const json& t = require(c, v, p, "type", " (one of: point, spot, disk, rect, laser)");
  std::string type = getString(c, t, child(p, "type"));
  Keys allowed = {"type", "name", "power_w", "spd"};
  if (type == "point") {
    light.type = LightType::Point;
    allowed.insert(allowed.end(), {"position"});
  } else if (type == "spot") {
    light.type = LightType::Spot;
    allowed.insert(allowed.end(), {"position", "direction", "cone_deg"});
  } else if (type == "disk") {
    light.type = LightType::Disk;
    allowed.insert(allowed.end(), {"center", "normal", "radius_m"});
  } else if (type == "rect") {
    light.type = LightType::Rect;
    allowed.insert(allowed.end(), {"center", "normal", "size_m", "u_axis"});
  } else if (type == "laser") {
    light.type = LightType::Laser;
    allowed.insert(allowed.end(), {"origin", "direction", "radius_m"});
  } else {
    c.fail(child(p, "type"), fmt::format("unknown light type {}{} (valid types: {})", jsonQuoted(type),
                                         suggestion(type, kTypes), joinKeys(kTypes)));
  }
  checkObject(c, v, p, allowed, fmt::format("a {} light", type));

  auto vec = [&](const char* key) { return getPoint(c, require(c, v, p, key), child(p, key)); };
  auto dir = [&](const char* key) { return getDirection(c, require(c, v, p, key), child(p, key)); };
  switch (light.type) {
    case LightType::Point: light.position = vec("position"); break;
    case LightType::Spot: {
      light.position = vec("position");
      light.direction = dir("direction");
      std::string cp = child(p, "cone_deg");
      const json& cone = require(c, v, p, "cone_deg", " (half angle of the cone, in degrees)");
      if (!cone.is_number() || !std::isfinite(cone.get<double>()) || !(cone.get<double>() > 0.0) ||
          !(cone.get<double>() <= 180.0))
        c.fail(cp, fmt::format("must be a half angle in degrees, > 0 and <= 180 (got {})", describe(cone)));
      light.coneHalfAngleDeg = cone.get<double>();
      break;
    }
    case LightType::Disk:
      light.position = vec("center");
      light.direction = dir("normal");
      light.radiusM = getLength(c, require(c, v, p, "radius_m"), child(p, "radius_m"));
      break;
    case LightType::Rect: {
      light.position = vec("center");
      light.direction = dir("normal");
      std::string sp = child(p, "size_m");
      const json& size = require(c, v, p, "size_m", " ([width along u_axis, height], in metres)");
      if (!size.is_array() || size.size() != 2)
        c.fail(sp, fmt::format("must be an array of 2 numbers > 0 [width, height] (got {})", describe(size)));
      for (size_t i = 0; i < 2; ++i) {
        const json& e = size[i];
        if (!e.is_number() || !std::isfinite(e.get<double>()) || !(e.get<double>() > 0.0) ||
            e.get<double>() > kMaxCoordinateM)
          c.fail(child(sp, i), fmt::format("must be a length in metres, > 0 and <= {:g} (got {}); a rect light needs "
                                           "a non-zero area",
                                           kMaxCoordinateM, describe(e)));
        light.sizeM[int(i)] = e.get<double>();
      }
      if (!(light.sizeM.x * light.sizeM.y > 0.0) || !std::isfinite(light.sizeM.x * light.sizeM.y))
        c.fail(sp, fmt::format("the rect's area {} x {} m² is not a positive finite number", fmtNum(light.sizeM.x),
                               fmtNum(light.sizeM.y)));
      if (auto* u = find(v, "u_axis")) {
        std::string up = child(p, "u_axis");
        glm::dvec3 axis = getDirection(c, *u, up);
        glm::dvec3 ortho = axis - light.direction * glm::dot(light.direction, axis);
        if (glm::length(glm::cross(axis, light.direction)) < kCollinearEps || !safeNormalize(ortho))
          c.fail(up, fmt::format("{} is parallel to the normal; u_axis must lie (roughly) in the rect's plane",
                                 describe(*u)));
        light.uAxis = *safeNormalize(ortho);
      } else {
        light.uAxis = defaultTangent(light.direction);
      }
      break;
    }
    case LightType::Laser:
      light.position = vec("origin");
      light.direction = dir("direction");
      light.radiusM = getLength(c, require(c, v, p, "radius_m"), child(p, "radius_m"));
      break;
  }
  // Spot, disk and laser get a tangent too (same rule as the rect default),
  // so every axis-bearing light carries a valid perpendicular frame.
  if (light.type == LightType::Spot || light.type == LightType::Disk || light.type == LightType::Laser)
    light.uAxis = defaultTangent(light.direction);

  light.powerW = getNonNegative(c, require(c, v, p, "power_w", " (radiant flux in watts)"), child(p, "power_w"));
  parseSpd(c, require(c, v, p, "spd"), child(p, "spd"), range, light);
  return light;
}

RenderSettings parseRender(const Ctx& c, const json& v, const std::string& p) {
  checkObject(c, v, p, {"beams", "seed"}, "render");
  RenderSettings r;
  if (auto* x = find(v, "beams")) r.beams = getU64(c, *x, child(p, "beams"), 1);
  if (auto* x = find(v, "seed")) r.seed = getU64(c, *x, child(p, "seed"), 0);
  return r;
}

}  // namespace

Scene parseScene(const std::string& jsonText, const fs::path& file) {
  Ctx c;
  c.file = file.string();
  c.dir = file.parent_path();
  if (c.dir.empty()) c.dir = ".";

  json root = parseJson(c, jsonText);
  static const Keys kTop = {"spectrum", "observer", "camera", "lights", "render"};
  if (!root.is_object()) c.fail("", fmt::format("the top level must be a JSON object (got {})", describe(root)));
  checkObject(c, root, "", kTop, "the top level");

  Scene scene;
  if (auto* x = find(root, "spectrum")) scene.spectrum = parseSpectrum(c, *x, "/spectrum");
  if (auto* x = find(root, "observer")) {
    static const Keys kObservers = {"CIE1931_2", "CIE1964_10"};
    std::string obs = getString(c, *x, "/observer");
    if (std::find(kObservers.begin(), kObservers.end(), obs) == kObservers.end())
      c.fail("/observer", fmt::format("unknown observer {}{} (valid: {})", jsonQuoted(obs), suggestion(obs, kObservers),
                                      joinKeys(kObservers)));
    scene.observer = obs;
  }
  scene.camera = parseCamera(c, require(c, root, "", "camera"), "/camera");

  const json& lights = require(c, root, "", "lights");
  if (!lights.is_array() || lights.empty())
    c.fail("/lights", fmt::format("must be a non-empty array of lights (got {})", describe(lights)));
  double total = 0.0;
  for (size_t i = 0; i < lights.size(); ++i) {
    scene.lights.push_back(parseLight(c, lights[i], child("/lights", i), scene.spectrum));
    total += scene.lights.back().powerW;
  }
  if (!std::isfinite(total)) c.fail("/lights", "the total power_w of all lights overflows");
  if (!(total > 0.0)) c.fail("/lights", "no light emits power: every power_w is 0");

  if (auto* x = find(root, "render")) scene.render = parseRender(c, *x, "/render");

  scene.sourcePath = file;
  scene.sourceSha256 = sceneSha256Hex(jsonText);
  return scene;
}

Scene loadScene(const fs::path& file) {
  Ctx c;
  c.file = file.string();
  std::error_code ec;
  auto status = fs::status(file, ec);
  if (!fs::exists(status)) c.fail("", "scene file not found");
  if (fs::is_directory(status)) c.fail("", "is a directory, not a scene file");
  std::ifstream in(file, std::ios::binary);
  if (!in) c.fail("", fmt::format("cannot open the scene file ({})", std::strerror(errno)));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) c.fail("", "error while reading the scene file");
  return parseScene(text, file);
}

}  // namespace spectrace

namespace spectrace {
namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

void validateScene(const Scene& scene) {
  const std::string file = scene.sourcePath.empty() ? std::string("<scene>") : scene.sourcePath.string();
  auto fail = [&](const std::string& field, const std::string& what) {
    throw SceneError(file + ": " + field + ": " + what);
  };
  const SpectrumRange& range = scene.spectrum;
  if (!(std::isfinite(range.minNm) && range.minNm > 0.0 && range.maxNm > range.minNm && std::isfinite(range.maxNm)))
    fail("/spectrum", "needs 0 < min_nm < max_nm, both finite");
  if (range.bins < 1) fail("/spectrum/bins", "must be at least 1");
  const Camera& camera = scene.camera;
  if (!finite(camera.position)) fail("/camera/position", "must be finite");
  if (!finite(camera.lookAt)) fail("/camera/look_at", "must be finite");
  if (!finite(camera.up)) fail("/camera/up", "must be finite");
  const glm::dvec3 view = camera.lookAt - camera.position;
  if (!(glm::length(view) > 0.0)) fail("/camera/look_at", "equals position, so there is no viewing direction");
  if (!(glm::length(glm::cross(glm::normalize(view), camera.up)) > 1e-9 * glm::length(camera.up)))
    fail("/camera/up", "is zero or parallel to the viewing direction");
  if (!(camera.sensorWidthM > 0.0 && std::isfinite(camera.sensorWidthM) && camera.sensorHeightM > 0.0 &&
        std::isfinite(camera.sensorHeightM)))
    fail("/camera/sensor", "width_m and height_m must be finite and > 0");
  if (camera.pixelsX < 1 || camera.pixelsY < 1) fail("/camera/sensor/pixels", "must be at least 1 x 1");
  if (camera.pinhole && !(camera.pinhole->distanceM > 0.0 && camera.pinhole->radiusM > 0.0 &&
                          std::isfinite(camera.pinhole->distanceM) && std::isfinite(camera.pinhole->radiusM)))
    fail("/camera/pinhole", "distance_m and radius_m must be finite and > 0");
  if (scene.lights.empty()) fail("/lights", "there are no lights");
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    const std::string at = light.label.empty() ? "/lights/" + std::to_string(i) : light.label;
    if (!finite(light.position)) fail(at + "/position", "must be finite");
    if (!(std::isfinite(light.powerW) && light.powerW >= 0.0)) fail(at + "/power_w", "must be finite and >= 0");
    if (light.type != LightType::Point) {
      if (!finite(light.direction) || !(glm::length(light.direction) > 0.0))
        fail(at + "/direction", "must be finite and not zero-length");
    }
    auto positive = [&](double v, const char* field) {
      if (!(v > 0.0 && std::isfinite(v))) fail(at + "/" + field, "must be finite and > 0 (a light needs a size)");
    };
    switch (light.type) {
      case LightType::Spot:
        if (!(light.coneHalfAngleDeg > 0.0 && light.coneHalfAngleDeg <= 180.0)) fail(at + "/cone_deg", "must be in (0, 180]");
        break;
      case LightType::Disk:
      case LightType::Laser: positive(light.radiusM, "radius_m"); break;
      case LightType::Rect: {
        positive(light.sizeM.x, "size_m");
        positive(light.sizeM.y, "size_m");
        const glm::dvec3 n = glm::normalize(light.direction);
        if (!finite(light.uAxis) || !(glm::length(light.uAxis - n * glm::dot(light.uAxis, n)) > 1e-9 * glm::length(light.uAxis)))
          fail(at + "/u_axis", "must not be zero or parallel to the normal");
        break;
      }
      case LightType::Point: break;
    }
  }
}

}  // namespace spectrace
