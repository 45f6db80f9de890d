#pragma once
// Inside the shapes module: reading an OBJ file's text, its positions and
// faces, checking every token on the way.
//
// Written here rather than taken from tinyobjloader (Debian's, which the
// mesh reader used before), because a reader that checks must tokenize
// every `v` and `f` line anyway, and tinyobjloader's own reading is not
// what the file says: it reads indices with atoi and numbers with a parser
// that stops at the first character it does not expect, so an index beyond
// an int's range wraps to another vertex, "nan" becomes 0 and "1,5" becomes
// 1, all without a word; and it builds each number from its digits with a
// power of ten a digit, which is not correctly rounded (two thirds of the
// benchmark sphere's 17-digit coordinates came out an ulp or more off) and
// took over a third of a million-triangle mesh's load. Here each coordinate is
// std::from_chars's correctly rounded double, read once.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

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

// What an OBJ file's text describes. Without a fault, every corner is a
// vertex of the file.
struct ObjText {
  std::optional<ObjTextFault> fault;   // the first refusal; the rest is then not read
  std::vector<glm::dvec3> vertices;    // each `v` line's x y z, in file order
  std::vector<uint32_t> corners;       // the faces' vertex indices (vertex 1 is 0), face after face
  std::vector<uint32_t> cornerCounts;  // each face's number of corners (at least 3), in file order
};

// Reads every `v` line (3, 4 or 6 OBJ numbers, all finite; the first three
// are the position, correctly rounded; one that underflows a double is a
// zero of its sign) and `f` line (at least 3 corners v, v/vt, v//vn or
// v/vt/vn; vertex indices from 1, or negative counting back from the last
// vertex defined so far, never beyond the file's vertices; texture and
// normal indices, which are not used, must be whole numbers other than 0).
// `l` and `p` lines (polylines and points, not used) must hold the same
// kind of corners. Other lines (vt, vn, g, o, s, usemtl, mtllib, ...) are
// not used. A UTF-8 byte order mark at the start is passed over. Lines end
// at "\n", "\r\n" or "\r"; a line's keyword is its first word (words part
// at spaces and tabs); "#" starts a comment. The fault reported is the
// first in file order, except for a positive index beyond the file's
// vertices, which is known only at the end: then the largest such index is
// named.
ObjText readObjText(std::string_view text);
// The same, the text read in parts at once: [0, splits[0]), [splits[0],
// splits[1]), ... [splits.back(), end), each split just after a "\n" and in
// increasing order, any byte order mark already removed; readObjText
// splits a large text so. What it returns does not depend on the splits
// (obj_text_test reads texts split at every line).
ObjText readObjTextInParts(std::string_view text, const std::vector<size_t>& splits);

}  // namespace spectrace
