#pragma once
// Reading fields of a JSON document with messages a person can act on: every
// problem becomes "<file>: <json pointer>: <what is wrong>", e.g.
// "scene.json: /lights/2/power_w: must be a finite number >= 0 (got -1)".
// Knows JSON, not what the document describes: callers pass their own
// limits and choose the exception type (Source::raise).
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
// Declarations only: the full JSON header takes seconds to parse, and most
// files that reach this one (through the unit types' headers) never touch
// a JSON value. Those that do include <nlohmann/json.hpp> themselves.
#include <nlohmann/json_fwd.hpp>

namespace spectrace::json_fields {

using Json = nlohmann::json;
using Keys = std::vector<std::string_view>;

// Thrown by Source::fail when the source names no exception of its own.
struct JsonFieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// JSON pointers (RFC 6901): "~" and "/" in a key are escaped.
std::string escapeToken(std::string_view key);
std::string child(const std::string& ptr, std::string_view key);
std::string child(const std::string& ptr, size_t index);

std::string jsonQuoted(std::string_view s);
std::string joinKeys(const Keys& keys);
// A number as people write it: shortest round-trip form ("0.5", "532").
std::string fmtNum(double x);
// A short description of a JSON value for "(got ...)".
std::string describe(const Json& v);
// Case-insensitive Levenshtein distance.
size_t editDistance(std::string_view a, std::string_view b);
// "; did you mean "x"?" when one candidate is close to `word` (by edit
// distance, or holding it or held by it, case aside: "BK7" and "N-BK7"),
// else "".
std::string suggestion(std::string_view word, const Keys& candidates);

// The document being read: names it in messages and says how to fail.
struct Source {
  std::string file;           // as shown in messages
  std::filesystem::path dir;  // folder relative paths in the document resolve against
  std::string note;           // appended to messages, e.g. ` (light "desk lamp")`
  // Throws the caller's exception with the whole message; when null (or if
  // it returns), JsonFieldError is thrown.
  void (*raise)(const std::string& message) = nullptr;

  [[noreturn]] void fail(const std::string& ptr, const std::string& what) const;
  // A path the document names, as written when absolute, else against dir.
  std::filesystem::path resolve(const std::filesystem::path& path) const {
    return path.is_absolute() ? path : (dir / path).lexically_normal();
  }
};

// Arrays and objects nest at most this deep in any JSON we read: scenes need
// 5 levels; deeper input is refused at once, before it costs memory.
inline constexpr int kMaxJsonDepth = 64;

// Parses `text` (comments tolerated); syntax errors name line, column and
// byte, a key repeated in one object is an error (nlohmann would keep
// the last), and so is nesting deeper than kMaxJsonDepth.
Json parseJson(const Source& c, const std::string& text);

const Json* find(const Json& obj, const std::string& key);
const Json& require(const Source& c, const Json& obj, const std::string& ptr, const std::string& key,
                    std::string_view hint = {});
// Checks that `v` is an object whose keys are all in `allowed`.
void checkObject(const Source& c, const Json& v, const std::string& ptr, const Keys& allowed, std::string_view what);

double getNumber(const Source& c, const Json& v, const std::string& ptr);
double getPositive(const Source& c, const Json& v, const std::string& ptr);
// A length in metres: > 0 and at most `maxM`.
double getLength(const Source& c, const Json& v, const std::string& ptr, double maxM);
double getNonNegative(const Source& c, const Json& v, const std::string& ptr);
// An integer in [lo, hi]; integral floats such as 1e8 are accepted.
int64_t getInt(const Source& c, const Json& v, const std::string& ptr, int64_t lo, int64_t hi);
// An unsigned 64-bit integer >= lo; integral floats below 2^64 are accepted.
uint64_t getU64(const Source& c, const Json& v, const std::string& ptr, uint64_t lo);
std::string getString(const Source& c, const Json& v, const std::string& ptr, bool allowEmpty = false);
// [x, y, z]; with `limit`, every |component| must be <= limit.
glm::dvec3 getVec3(const Source& c, const Json& v, const std::string& ptr,
                   double limit = std::numeric_limits<double>::infinity());
// A position in metres, every |coordinate| <= maxM.
glm::dvec3 getPoint(const Source& c, const Json& v, const std::string& ptr, double maxM);
// A non-zero [x, y, z], returned as a unit vector.
glm::dvec3 getDirection(const Source& c, const Json& v, const std::string& ptr);
std::vector<double> getNumberArray(const Source& c, const Json& v, const std::string& ptr);

// Unit vector, robust against huge and tiny components; nullopt for zero.
std::optional<glm::dvec3> safeNormalize(const glm::dvec3& v);

}  // namespace spectrace::json_fields
