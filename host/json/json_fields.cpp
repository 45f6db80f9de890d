#include "json/json_fields.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

namespace spectrace::json_fields {

std::string fmtNum(double x) { return fmt::format("{}", x); }

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

std::string jsonQuoted(std::string_view s) { return Json(std::string(s)).dump(); }

std::string joinKeys(const Keys& keys) {
  std::string out;
  for (auto k : keys) {
    if (!out.empty()) out += ", ";
    out += k;
  }
  return out;
}

std::string describe(const Json& v) {
  switch (v.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float: return v.dump();
    case Json::value_t::string: {
      std::string s = v.get<std::string>();
      if (s.size() <= 48) return jsonQuoted(s);
      size_t cut = 45;
      while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;  // UTF-8 boundary
      return jsonQuoted(s.substr(0, cut)) + "...";
    }
    case Json::value_t::array: {
      bool small = v.size() <= 4 && std::all_of(v.begin(), v.end(), [](const Json& e) { return e.is_primitive(); });
      if (small) {
        std::string out = "[";
        for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + describe(v[i]);
        return out + "]";
      }
      return fmt::format("an array of {} element{}", v.size(), v.size() == 1 ? "" : "s");
    }
    case Json::value_t::object: return "an object";
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

std::string suggestion(std::string_view word, const Keys& candidates) {
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
  if (!best.empty() && bestDistance <= limit) return fmt::format("; did you mean {}?", jsonQuoted(best));
  // Else a candidate holding the word or held by it, case aside: catalogue
  // names carry prefixes the edit distance counts in full ("BK7" for
  // "N-BK7"). Three characters at least, so that a match means something.
  const auto lower = [](std::string_view text) {
    std::string out(text);
    for (char& ch : out) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    return out;
  };
  const std::string w = lower(word);
  best = {};
  bestDistance = std::numeric_limits<size_t>::max();
  for (auto c : candidates) {
    const std::string l = lower(c);
    const bool holds = w.size() >= 3 && l.find(w) != std::string::npos;
    const bool held = l.size() >= 3 && w.find(l) != std::string::npos;
    if ((holds || held) && editDistance(word, c) < bestDistance) {
      bestDistance = editDistance(word, c);
      best = c;
    }
  }
  return best.empty() ? "" : fmt::format("; did you mean {}?", jsonQuoted(best));
}

void Source::fail(const std::string& ptr, const std::string& what) const {
  // The root's pointer is "", shown as "/" so the message stays readable.
  const std::string message = fmt::format("{}: {}: {}{}", file, ptr.empty() ? "/" : ptr, what, note);
  if (raise) raise(message);
  throw JsonFieldError(message);
}

namespace {

// ---------------------------------------------------------------------------
// Parsing, with duplicate keys rejected (nlohmann would keep the last).

struct DuplicateKey {
  std::string ptr;
  std::string key;
};

struct TooDeep {
  std::string ptr;
};

}  // namespace

Json parseJson(const Source& c, const std::string& text) {
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
    // Checked here, as the level opens: each frame holds its pointer, so
    // unbounded depth would cost memory quadratic in the depth.
    if (stack.size() >= size_t(kMaxJsonDepth)) throw TooDeep{std::move(ptr)};
    stack.push_back(Frame{isArray, 0, std::move(ptr), {}, {}});
  };
  Json::parser_callback_t callback = [&](int, Json::parse_event_t event, Json& parsed) {
    switch (event) {
      case Json::parse_event_t::object_start: beginChild(false); break;
      case Json::parse_event_t::array_start: beginChild(true); break;
      case Json::parse_event_t::object_end:
      case Json::parse_event_t::array_end:
        if (!stack.empty()) stack.pop_back();
        break;
      case Json::parse_event_t::key: {
        if (stack.empty()) break;
        Frame& f = stack.back();
        std::string key = parsed.get<std::string>();
        if (!f.keys.insert(key).second) throw DuplicateKey{child(f.ptr, key), key};
        f.key = std::move(key);
        break;
      }
      case Json::parse_event_t::value:
        if (!stack.empty() && stack.back().isArray) ++stack.back().next;
        break;
    }
    return true;
  };
  try {
    return Json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const DuplicateKey& d) {
    c.fail(d.ptr, fmt::format("duplicate key {} (each key may appear only once per object)", jsonQuoted(d.key)));
  } catch (const TooDeep& d) {
    c.fail(d.ptr.size() > 80 ? d.ptr.substr(0, 80) + "..." : d.ptr,
           fmt::format("arrays and objects nest more than {} levels deep, the most spectrace reads", kMaxJsonDepth));
  } catch (const Json::parse_error& e) {
    std::string what = e.what();
    if (auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    c.fail("", fmt::format("invalid JSON: {} (byte {})", what, e.byte));
  } catch (const Json::exception& e) {
    std::string what = e.what();
    if (auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    c.fail("", fmt::format("invalid JSON: {}", what));
  }
}

// ---------------------------------------------------------------------------
// Typed field access

const Json* find(const Json& obj, const std::string& key) {
  auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

const Json& require(const Source& c, const Json& obj, const std::string& ptr, const std::string& key,
                    std::string_view hint) {
  const Json* v = find(obj, key);
  if (!v) c.fail(child(ptr, key), fmt::format("missing required field {}{}", jsonQuoted(key), hint));
  return *v;
}

void checkObject(const Source& c, const Json& v, const std::string& ptr, const Keys& allowed, std::string_view what) {
  if (!v.is_object()) c.fail(ptr, fmt::format("{} must be an object (got {})", what, describe(v)));
  for (const auto& [key, value] : v.items()) {
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      c.fail(child(ptr, key), fmt::format("unknown key {} in {}{} (allowed keys: {})", jsonQuoted(key), what,
                                          suggestion(key, allowed), joinKeys(allowed)));
  }
}

double getNumber(const Source& c, const Json& v, const std::string& ptr) {
  if (!v.is_number()) c.fail(ptr, fmt::format("must be a finite number (got {})", describe(v)));
  double d = v.get<double>();
  if (!std::isfinite(d)) c.fail(ptr, fmt::format("must be a finite number (got {})", describe(v)));
  return d;
}

double getPositive(const Source& c, const Json& v, const std::string& ptr) {
  if (!v.is_number() || !std::isfinite(v.get<double>()) || !(v.get<double>() > 0.0))
    c.fail(ptr, fmt::format("must be a finite number > 0 (got {})", describe(v)));
  return v.get<double>();
}

double getLength(const Source& c, const Json& v, const std::string& ptr, double maxM) {
  double d = getPositive(c, v, ptr);
  if (d > maxM)
    c.fail(ptr, fmt::format("must be a length in metres, > 0 and <= {:g} (got {})", maxM, describe(v)));
  return d;
}

double getNonNegative(const Source& c, const Json& v, const std::string& ptr) {
  if (!v.is_number() || !std::isfinite(v.get<double>()) || !(v.get<double>() >= 0.0))
    c.fail(ptr, fmt::format("must be a finite number >= 0 (got {})", describe(v)));
  return v.get<double>() == 0.0 ? 0.0 : v.get<double>();  // no -0
}

int64_t getInt(const Source& c, const Json& v, const std::string& ptr, int64_t lo, int64_t hi) {
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

uint64_t getU64(const Source& c, const Json& v, const std::string& ptr, uint64_t lo) {
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

std::string getString(const Source& c, const Json& v, const std::string& ptr, bool allowEmpty) {
  if (!v.is_string()) c.fail(ptr, fmt::format("must be a string (got {})", describe(v)));
  std::string s = v.get<std::string>();
  if (s.empty() && !allowEmpty) c.fail(ptr, "must be a non-empty string");
  return s;
}

glm::dvec3 getVec3(const Source& c, const Json& v, const std::string& ptr, double limit) {
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

glm::dvec3 getPoint(const Source& c, const Json& v, const std::string& ptr, double maxM) {
  return getVec3(c, v, ptr, maxM);
}

std::optional<glm::dvec3> safeNormalize(const glm::dvec3& v) {
  double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(m > 0.0) || !std::isfinite(m)) return std::nullopt;
  glm::dvec3 w = v / m;
  return w / glm::length(w);
}

glm::dvec3 getDirection(const Source& c, const Json& v, const std::string& ptr) {
  glm::dvec3 d = getVec3(c, v, ptr);
  auto n = safeNormalize(d);
  if (!n) c.fail(ptr, fmt::format("must not be zero-length (got {})", describe(v)));
  return *n;
}

std::vector<double> getNumberArray(const Source& c, const Json& v, const std::string& ptr) {
  if (!v.is_array() || v.empty())
    c.fail(ptr, fmt::format("must be a non-empty array of finite numbers (got {})", describe(v)));
  std::vector<double> out;
  out.reserve(v.size());
  for (size_t i = 0; i < v.size(); ++i) out.push_back(getNumber(c, v[i], child(ptr, i)));
  return out;
}

}  // namespace spectrace::json_fields
