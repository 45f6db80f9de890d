#include "shapes/obj_text.h"

#include <algorithm>
#include <charconv>
#include <limits>
#include <vector>

#include <fmt/format.h>

namespace spectrace {

namespace {

constexpr size_t kShownTokenBytes = 40;

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isSign(char c) { return c == '+' || c == '-'; }

size_t digitsAt(std::string_view s, size_t i) {
  size_t j = i;
  while (j < s.size() && isDigit(s[j])) ++j;
  return j - i;
}

std::string shown(std::string_view token) {
  std::string out = "\"";
  for (unsigned char c : token.substr(0, kShownTokenBytes)) {
    if (c == '"' || c == '\\')
      out += fmt::format("\\{}", char(c));
    else if (c >= 0x20 && c < 0x7f)
      out += char(c);
    else
      out += fmt::format("\\x{:02x}", c);
  }
  return out + (token.size() > kShownTokenBytes ? "...\"" : "\"");
}

// Character searches by plain loops: libstdc++'s find_first_of and
// find_first_not_of call memchr once for every character they pass, which
// was half of this check's time on a million-triangle file.
bool isBlank(char c) { return c == ' ' || c == '\t'; }

size_t findBlank(std::string_view s, size_t from) {
  while (from < s.size() && !isBlank(s[from])) ++from;
  return from;
}

size_t findNonBlank(std::string_view s, size_t from) {
  while (from < s.size() && isBlank(s[from])) ++from;
  return from;
}

// The text's lines as tinyobjloader's safeGetline splits them.
class Lines {
 public:
  explicit Lines(std::string_view text) : rest_(text) {}
  bool next(std::string_view& line) {
    if (rest_.empty()) return false;
    size_t end = 0;
    while (end < rest_.size() && rest_[end] != '\n' && rest_[end] != '\r') ++end;
    line = rest_.substr(0, end);
    const bool crlf = end + 1 < rest_.size() && rest_[end] == '\r' && rest_[end + 1] == '\n';
    rest_.remove_prefix(std::min(rest_.size(), end + (crlf ? 2 : 1)));
    ++number_;
    return true;
  }
  uint64_t number() const { return number_; }

 private:
  std::string_view rest_;
  uint64_t number_ = 0;
};

// Splits at spaces and tabs, as tinyobjloader does, into `out` (reused:
// a large file has millions of lines).
void splitTokens(std::string_view s, std::vector<std::string_view>& out) {
  out.clear();
  size_t i = 0;
  while ((i = findNonBlank(s, i)) < s.size()) {
    const size_t end = findBlank(s, i);
    out.push_back(s.substr(i, end - i));
    i = end;
  }
}

bool spellsNanOrInf(std::string_view s) {
  if (!s.empty() && isSign(s[0])) s.remove_prefix(1);
  std::string lower(s.substr(0, 9));
  for (char& c : lower) c = char(c | 0x20);
  return lower == "nan" || lower == "inf" || lower == "infinity" || (lower.starts_with("nan(") && s.ends_with(")"));
}

// For a number in OBJ syntax: whether its magnitude is >= 1, from the place
// of its first non-zero digit and its exponent (saturated: only the sign
// matters), to tell overflow from underflow when from_chars says neither
// fits.
bool atLeastOne(std::string_view s) {
  if (isSign(s[0])) s.remove_prefix(1);
  const size_t whole = digitsAt(s, 0);
  const size_t point = whole < s.size() && s[whole] == '.' ? 1 : 0;
  const size_t fraction = digitsAt(s, whole + point);
  const std::string_view digits = s.substr(0, whole + point + fraction);
  const size_t first = digits.find_first_of("123456789");
  if (first == std::string_view::npos) return false;
  int64_t place = first < whole ? int64_t(whole - first - 1) : -int64_t(first - whole);
  const size_t e = whole + point + fraction;
  if (e < s.size()) {
    const std::string_view exponent = s.substr(e + 1);
    const bool negative = exponent[0] == '-';
    int64_t value = 0;
    for (char c : exponent.substr(isSign(exponent[0]) ? 1 : 0))
      value = std::min<int64_t>(value * 10 + (c - '0'), 1'000'000'000'000);
    place += negative ? -value : value;
  }
  return place >= 0;
}

bool overflowsDouble(std::string_view s) {
  if (s[0] == '+') s.remove_prefix(1);  // from_chars takes no '+'
  double value = 0.0;
  const auto result = std::from_chars(s.data(), s.data() + s.size(), value, std::chars_format::general);
  return result.ec == std::errc::result_out_of_range && atLeastOne(s);
}

// A whole number: its magnitude (saturated at 2^64 - 1, `beyond` set) and
// sign, or nullopt when the token is not [+-]digits.
struct WholeNumber {
  uint64_t magnitude = 0;
  bool beyond = false;  // more than 2^64 - 1
  bool negative = false;
};

std::optional<WholeNumber> readWhole(std::string_view s) {
  WholeNumber n;
  if (!s.empty() && isSign(s[0])) {
    n.negative = s[0] == '-';
    s.remove_prefix(1);
  }
  if (s.empty() || digitsAt(s, 0) != s.size()) return std::nullopt;
  const auto result = std::from_chars(s.data(), s.data() + s.size(), n.magnitude);
  if (result.ec == std::errc::result_out_of_range) n.beyond = true, n.magnitude = std::numeric_limits<uint64_t>::max();
  return n;
}

std::string vertexNumber(const WholeNumber& n) {
  return n.beyond ? "a vertex beyond 2^64" : fmt::format("vertex {}", n.magnitude);
}

// The scan's state: counts so far, the first fault, the largest positive
// vertex index and where it was.
class Checker {
 public:
  void vertexLine(std::string_view line, std::string_view rest) {
    ++result_.vertices;
    splitTokens(rest, tokens_);
    const auto& numbers = tokens_;
    if (numbers.size() != 3 && numbers.size() != 4 && numbers.size() != 6)
      return fail(line, fmt::format("vertex {} has {} numbers; a vertex is x y z, optionally followed by w or by r g b",
                                    result_.vertices, numbers.size()));
    for (std::string_view number : numbers) {
      if (spellsNanOrInf(number))
        return fail(number, fmt::format("vertex {} has a coordinate that is not finite (nan and inf are refused)",
                                        result_.vertices));
      if (!isObjNumber(number))
        return fail(number, fmt::format("vertex {} has a coordinate that is not a number in OBJ syntax (a decimal "
                                        "such as -1.5 or 2.5e-3)",
                                        result_.vertices));
      if (overflowsDouble(number))
        return fail(number, fmt::format("vertex {} has a coordinate that is not finite (beyond the range of a double)",
                                        result_.vertices));
    }
  }

  void faceLine(std::string_view line, std::string_view rest) {
    ++result_.faces;
    splitTokens(rest, tokens_);
    const auto& corners = tokens_;
    if (corners.size() < 3)
      return fail(line, fmt::format("face {} has {} corners; a face needs at least 3", result_.faces, corners.size()));
    for (std::string_view corner : corners)
      if (!checkCorner(corner)) return;
  }

  ObjTextCheck finish() {
    if (!result_.fault && largest_.magnitude > result_.vertices)
      result_.fault = ObjTextFault{
          largestLine_, largestToken_,
          fmt::format("face {} refers to {}, but the file has {} vertices{}", largestFace_, vertexNumber(largest_),
                      result_.vertices, result_.vertices ? fmt::format(" (1 to {})", result_.vertices) : "")};
    return std::move(result_);
  }

  bool failed() const { return result_.fault.has_value(); }
  void atLine(uint64_t number) { line_ = number; }

 private:
  void fail(std::string_view token, std::string what) {
    result_.fault = ObjTextFault{line_, shown(token), std::move(what)};
  }

  // v, v/vt, v//vn or v/vt/vn.
  bool checkCorner(std::string_view corner) {
    std::string_view parts[3];
    size_t count = 0;
    for (size_t start = 0;;) {
      if (count == 3) return badCorner(corner);
      const size_t slash = std::min(corner.find('/', start), corner.size());
      parts[count++] = corner.substr(start, slash - start);
      if (slash == corner.size()) break;
      start = slash + 1;
    }
    for (size_t k = 0; k < count; ++k) {
      if (k == 1 && count == 3 && parts[1].empty()) continue;  // v//vn
      const auto n = readWhole(parts[k]);
      if (!n) return badCorner(corner);
      if (!checkIndex(corner, k, *n)) return false;
    }
    return true;
  }

  bool badCorner(std::string_view corner) {
    fail(corner, fmt::format("face {} has a corner that is not v, v/vt, v//vn or v/vt/vn (each a whole number)",
                             result_.faces));
    return false;
  }

  // Part k of a corner: 0 the vertex, 1 the texture coordinate, 2 the normal.
  bool checkIndex(std::string_view corner, size_t k, const WholeNumber& n) {
    static constexpr const char* kWhat[3] = {"vertex", "texture coordinate", "normal"};
    if (n.magnitude == 0) {
      fail(corner,
           fmt::format("face {} refers to {} 0; OBJ numbers them from 1 (or from -1 back)", result_.faces, kWhat[k]));
      return false;
    }
    if (k != 0) return true;
    if (n.negative && n.magnitude > result_.vertices) {
      fail(corner,
           fmt::format("face {} refers to vertex before the first ({} back from the {} vertices defined so far)",
                       result_.faces, n.beyond ? "more than 2^64" : std::to_string(n.magnitude), result_.vertices));
      return false;
    }
    if (!n.negative && n.magnitude > largest_.magnitude) {
      largest_ = n;
      largestLine_ = line_;
      largestToken_ = shown(corner);
      largestFace_ = result_.faces;
    }
    return true;
  }

  ObjTextCheck result_;
  std::vector<std::string_view> tokens_;
  WholeNumber largest_;
  uint64_t line_ = 0;
  uint64_t largestLine_ = 0, largestFace_ = 0;
  std::string largestToken_;
};

}  // namespace

bool isObjNumber(std::string_view s) {
  size_t i = !s.empty() && isSign(s[0]) ? 1 : 0;
  const size_t whole = digitsAt(s, i);
  i += whole;
  size_t fraction = 0;
  if (i < s.size() && s[i] == '.') {
    fraction = digitsAt(s, i + 1);
    i += 1 + fraction;
  }
  if (whole == 0 && fraction == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && isSign(s[i])) ++i;
    const size_t exponent = digitsAt(s, i);
    if (exponent == 0) return false;
    i += exponent;
  }
  return i == s.size();
}

ObjTextCheck checkObjText(std::string_view text) {
  Checker checker;
  Lines lines(text);
  std::string_view line;
  while (!checker.failed() && lines.next(line)) {
    checker.atLine(lines.number());
    // The keyword as tinyobjloader finds it ("v" then a space or tab); the
    // rest up to a comment.
    const size_t start = findNonBlank(line, 0);
    const size_t keywordEnd = findBlank(line, start);
    const std::string_view keyword = line.substr(start, keywordEnd - start);
    if (keyword != "v" && keyword != "f") continue;
    std::string_view rest = line.substr(keywordEnd);
    rest = rest.substr(0, rest.find('#'));
    const std::string_view whole = line.substr(start);
    if (keyword == "v")
      checker.vertexLine(whole, rest);
    else
      checker.faceLine(whole, rest);
  }
  return checker.finish();
}

}  // namespace spectrace
