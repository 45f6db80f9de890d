#pragma once
// Inside the scene module: the checks on an OBJ file's text that
// tinyobjloader does not make. It reads indices with atoi and numbers with
// a parser that stops at the first character it does not expect, so an
// index beyond an int's range wraps to another vertex, "nan" becomes 0 and
// "1,5" becomes 1, all without a word. Patching that is not possible from
// outside the library, so the `v` and `f` lines are tokenized here as
// tinyobjloader splits them, and every token must be whole, in range and
// finite; tinyobjloader still reads the values (obj_mesh.cpp).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace spectrace {

// OBJ numbers are decimals: an optional sign, digits with an optional
// fraction (at least one digit, before or after the point), an optional
// exponent ("e" or "E", optional sign, digits). nan and inf spellings are
// not OBJ numbers and are refused.
bool isObjNumber(std::string_view token);

// A token of an OBJ file that is refused: its line (from 1), the token as
// shown in messages (quoted, bytes that are not printable ASCII escaped as
// \xNN, cut after 40 bytes) and what is wrong ("face 2 refers to vertex 9,
// but the file has 3 vertices (1 to 3)").
struct ObjTextFault {
  uint64_t line = 0;
  std::string token;
  std::string what;
};

struct ObjTextCheck {
  std::optional<ObjTextFault> fault;
  uint64_t vertices = 0;  // `v` lines
  uint64_t faces = 0;     // `f` lines
};

// Checks every `v` line (3, 4 or 6 OBJ numbers, all finite) and `f` line
// (at least 3 corners v, v/vt, v//vn or v/vt/vn; vertex indices from 1, or
// negative counting back from the last vertex defined so far, never beyond
// the file's vertices; texture and normal indices, which are not used, must
// be whole numbers other than 0). Lines end at "\n", "\r\n" or "\r", as for
// tinyobjloader; "#" starts a comment. The fault reported is the first in
// file order, except for a positive index beyond the file's vertices, which
// is known only at the end: then the largest such index is named.
ObjTextCheck checkObjText(std::string_view text);

}  // namespace spectrace
