#include "shapes/obj_text.h"

#include <algorithm>
#include <charconv>
#include <exception>
#include <limits>
#include <optional>
#include <thread>
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

// The number's correctly rounded double, for a token in OBJ syntax (see
// isObjNumber); nullopt when its magnitude is beyond a double's range. One
// too small for a denormal is a zero of its sign, as rounding makes it.
std::optional<double> objNumberValue(std::string_view s) {
  const bool negative = s[0] == '-';
  if (s[0] == '+') s.remove_prefix(1);  // from_chars takes no '+'
  double value = 0.0;
  const auto result = std::from_chars(s.data(), s.data() + s.size(), value, std::chars_format::general);
  if (result.ec == std::errc::result_out_of_range) {
    if (atLeastOne(s)) return std::nullopt;
    return negative ? -0.0 : 0.0;
  }
  return value;
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

// The elements whose corners are vertex indices: faces, and the polylines
// and point sets, which are checked alike but not used.
enum class Element { Face, Polyline, Points };

constexpr const char* kElementNoun[3] = {"face", "polyline (l)", "point set (p)"};

// The scan's state: what has been read, the first fault, the largest
// positive vertex index and where it was.
class Reader {
 public:
  // `verticesBefore`: vertices defined before the text this reader is
  // given (the second part of a file read in two; otherwise 0).
  explicit Reader(uint64_t verticesBefore = 0) : verticesBefore_(verticesBefore) {}

  void vertexLine(std::string_view line, std::string_view rest) {
    splitTokens(rest, tokens_);
    const auto& numbers = tokens_;
    const uint64_t vertex = defined() + 1;
    if (numbers.size() != 3 && numbers.size() != 4 && numbers.size() != 6)
      return fail(line, fmt::format("vertex {} has {} numbers; a vertex is x y z, optionally followed by w or by r g b",
                                    vertex, numbers.size()));
    double position[3] = {};
    for (size_t k = 0; k < numbers.size(); ++k) {
      const std::string_view number = numbers[k];
      if (!isObjNumber(number)) {
        if (spellsNanOrInf(number))
          return fail(number,
                      fmt::format("vertex {} has a coordinate that is not finite (nan and inf are refused)", vertex));
        return fail(number, fmt::format("vertex {} has a coordinate that is not a number in OBJ syntax (a decimal "
                                        "such as -1.5 or 2.5e-3)",
                                        vertex));
      }
      const std::optional<double> value = objNumberValue(number);
      if (!value)
        return fail(number, fmt::format("vertex {} has a coordinate that is not finite (beyond the range of a double)",
                                        vertex));
      if (k < 3) position[k] = *value;
    }
    result_.vertices.emplace_back(position[0], position[1], position[2]);
  }

  // A face, polyline or point set; a face's vertex indices are kept.
  void elementLine(Element element, std::string_view line, std::string_view rest) {
    element_ = element;
    ++counts_[int(element)];
    splitTokens(rest, tokens_);
    const auto& corners = tokens_;
    const size_t least = element == Element::Face ? 3 : 1;
    if (corners.size() < least)
      return fail(line, fmt::format("{} has {} corners; a {} needs at least {}", elementName(), corners.size(),
                                    kElementNoun[int(element)], least));
    for (std::string_view corner : corners) {
      uint32_t vertex = 0;
      if (!readCorner(corner, vertex)) return;
      if (element == Element::Face) result_.corners.push_back(vertex);
    }
    if (element == Element::Face) result_.cornerCounts.push_back(uint32_t(corners.size()));
  }

  ObjText finish() {
    const uint64_t vertices = result_.vertices.size();
    if (!result_.fault && largest_.magnitude > vertices)
      result_.fault = ObjTextFault{
          largestLine_, shown(largestToken_),
          fmt::format("{} {} refers to {}, but the file has {} vertices{}", kElementNoun[int(largestElement_)],
                      largestCount_, vertexNumber(largest_), vertices,
                      vertices ? fmt::format(" (1 to {})", vertices) : "")};
    return std::move(result_);
  }

  bool failed() const { return result_.fault.has_value(); }
  // What was read, without finish()'s check of the largest index.
  ObjText& read() { return result_; }
  const WholeNumber& largest() const { return largest_; }
  void atLine(uint64_t number) { line_ = number; }

 private:
  // "face 3": the element being read, for messages.
  std::string elementName() const { return fmt::format("{} {}", kElementNoun[int(element_)], counts_[int(element_)]); }

  void fail(std::string_view token, std::string what) {
    result_.fault = ObjTextFault{line_, shown(token), std::move(what)};
  }

  // v, v/vt, v//vn or v/vt/vn. `vertex` is v's index from 0; for a positive
  // index beyond the vertices read so far, the index (saturated), which
  // finish() checks against the whole file's.
  bool readCorner(std::string_view corner, uint32_t& vertex) {
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
      if (k == 0)
        vertex = uint32_t(n->negative ? defined() - n->magnitude
                                      : std::min<uint64_t>(n->magnitude - 1, std::numeric_limits<uint32_t>::max()));
    }
    return true;
  }

  bool badCorner(std::string_view corner) {
    fail(corner, fmt::format("{} has a corner that is not v, v/vt, v//vn or v/vt/vn (each a whole number)",
                             elementName()));
    return false;
  }

  // Part k of a corner: 0 the vertex, 1 the texture coordinate, 2 the normal.
  bool checkIndex(std::string_view corner, size_t k, const WholeNumber& n) {
    static constexpr const char* kWhat[3] = {"vertex", "texture coordinate", "normal"};
    if (n.magnitude == 0) {
      fail(corner,
           fmt::format("{} refers to {} 0; OBJ numbers them from 1 (or from -1 back)", elementName(), kWhat[k]));
      return false;
    }
    if (k != 0) return true;
    if (n.negative && n.magnitude > defined()) {
      fail(corner, fmt::format("{} refers to vertex before the first ({} back from the {} vertices defined so far)",
                               elementName(), n.beyond ? "more than 2^64" : std::to_string(n.magnitude), defined()));
      return false;
    }
    if (!n.negative && n.magnitude > largest_.magnitude) {
      largest_ = n;
      largestLine_ = line_;
      largestToken_ = corner;  // a view of the text, which outlives the reader
      largestElement_ = element_;
      largestCount_ = counts_[int(element_)];
    }
    return true;
  }

  uint64_t defined() const { return verticesBefore_ + result_.vertices.size(); }

  uint64_t verticesBefore_ = 0;
  ObjText result_;
  std::vector<std::string_view> tokens_;
  Element element_ = Element::Face;
  uint64_t counts_[3] = {};  // faces, polylines and point sets so far
  WholeNumber largest_;
  uint64_t line_ = 0;
  uint64_t largestLine_ = 0;
  std::string_view largestToken_;
  Element largestElement_ = Element::Face;
  uint64_t largestCount_ = 0;
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

namespace {

// A line's keyword, its first word; `start` and `end` are where it begins
// and ends in the line.
std::string_view lineKeyword(std::string_view line, size_t& start, size_t& end) {
  start = findNonBlank(line, 0);
  end = findBlank(line, start);
  return line.substr(start, end - start);
}

// Hands each `v`, `f`, `l` and `p` line of `text` to `reader`, until it
// fails.
void readLines(std::string_view text, Reader& reader) {
  Lines lines(text);
  std::string_view line;
  while (!reader.failed() && lines.next(line)) {
    reader.atLine(lines.number());
    size_t start = 0, keywordEnd = 0;
    const std::string_view keyword = lineKeyword(line, start, keywordEnd);
    if (keyword.size() != 1) continue;
    const char kind = keyword[0];
    if (kind != 'v' && kind != 'f' && kind != 'l' && kind != 'p') continue;
    // The rest up to a comment.
    std::string_view rest = line.substr(keywordEnd);
    rest = rest.substr(0, rest.find('#'));
    const std::string_view whole = line.substr(start);
    if (kind == 'v')
      reader.vertexLine(whole, rest);
    else
      reader.elementLine(kind == 'f' ? Element::Face : kind == 'l' ? Element::Polyline : Element::Points, whole, rest);
  }
}

// The lines whose keyword is `v`: the vertices a text defines, when it
// has no fault.
uint64_t vertexLines(std::string_view text) {
  Lines lines(text);
  std::string_view line;
  uint64_t count = 0;
  size_t start = 0, end = 0;
  while (lines.next(line)) count += lineKeyword(line, start, end) == "v" ? 1 : 0;
  return count;
}

ObjText readSerially(std::string_view text) {
  Reader reader;
  readLines(text, reader);
  return reader.finish();
}

}  // namespace

ObjText readObjText(std::string_view text) {
  // A UTF-8 byte order mark, which some exporters write, would otherwise
  // join the first line's keyword, and a first `v` line would go unread.
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  // Reading numbers is nearly all of a large mesh's load, so a large text
  // is read in parts at once, split after lines' ends: two per core, since
  // a file's vertex lines, which come first, take longer than its faces.
  constexpr size_t kLeastPartBytes = size_t(2) << 20;
  const size_t parts = std::min<size_t>(2 * std::max(1u, std::thread::hardware_concurrency()),
                                        text.size() / kLeastPartBytes);
  std::vector<size_t> splits;
  for (size_t k = 1; k < parts; ++k) {
    const size_t end = text.find('\n', std::max(text.size() * k / parts, splits.empty() ? 0 : splits.back()));
    if (end == std::string_view::npos) break;
    if (splits.empty() || end + 1 > splits.back()) splits.push_back(end + 1);
  }
  if (splits.empty()) return readSerially(text);
  return readObjTextInParts(text, splits);
}

ObjText readObjTextInParts(std::string_view text, const std::vector<size_t>& splits) {
  std::vector<std::string_view> parts;
  size_t begin = 0;
  for (size_t split : splits) {
    parts.push_back(text.substr(begin, split - begin));
    begin = split;
  }
  parts.push_back(text.substr(begin));
  const size_t n = parts.size();
  // work(k) for every part, each on a thread; what a part throws (running
  // out of memory) is thrown here, once all have ended.
  const auto eachPart = [n](const auto& work) {
    std::vector<std::exception_ptr> thrown(n);
    const auto guarded = [&](size_t k) {
      try {
        work(k);
      } catch (...) {
        thrown[k] = std::current_exception();
      }
    };
    {
      std::vector<std::jthread> threads;  // joined on every way out
      for (size_t k = 1; k < n; ++k) threads.emplace_back(guarded, k);
      guarded(0);
    }
    for (const std::exception_ptr& e : thrown)
      if (e) std::rethrow_exception(e);
  };
  // A part's negative indices count back from the vertices of every part
  // before it, so each part's vertex lines are counted first.
  std::vector<uint64_t> vertices(n);
  eachPart([&](size_t k) { vertices[k] = vertexLines(parts[k]); });
  std::vector<Reader> readers;
  readers.reserve(n);
  uint64_t before = 0;
  for (size_t k = 0; k < n; ++k) {
    readers.emplace_back(before);
    before += vertices[k];
  }
  eachPart([&](size_t k) { readLines(parts[k], readers[k]); });
  // A fault's message names its line, face and vertex numbers as the whole
  // file counts them, and the fault reported is the first in the file: the
  // text is read again in one part, which takes the time only for a file
  // that is refused. So does a count of a part's vertices that disagrees
  // with its reading, which a part without a fault cannot give.
  uint64_t largest = 0;
  for (size_t k = 0; k < n; ++k) {
    if (readers[k].failed() || readers[k].read().vertices.size() != vertices[k]) return readSerially(text);
    largest = std::max(largest, readers[k].largest().magnitude);
  }
  if (largest > before) return readSerially(text);
  ObjText all = std::move(readers[0].read());
  for (size_t k = 1; k < n; ++k) {
    ObjText& part = readers[k].read();
    all.vertices.insert(all.vertices.end(), part.vertices.begin(), part.vertices.end());
    all.corners.insert(all.corners.end(), part.corners.begin(), part.corners.end());
    all.cornerCounts.insert(all.cornerCounts.end(), part.cornerCounts.begin(), part.cornerCounts.end());
  }
  return all;
}

}  // namespace spectrace
