#include "json/json_fields.h"

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace spectrace::json_fields {
namespace {

// The message of what `f` throws ("" if nothing).
template <class F>
std::string messageOf(F&& f) {
  try {
    f();
  } catch (const JsonFieldError& e) {
    return e.what();
  }
  return "";
}

TEST(JsonFields, PointersEscapeTildeAndSlash) {
  EXPECT_EQ(escapeToken("a/b~c"), "a~1b~0c");
  EXPECT_EQ(child("/lights", size_t(2)), "/lights/2");
  EXPECT_EQ(child("", "x/y"), "/x~1y");
}

TEST(JsonFields, DescribeAndSuggest) {
  EXPECT_EQ(describe(Json::parse("[1, \"x\", null]")), "[1, \"x\", null]");
  EXPECT_EQ(describe(Json::parse("[1, 2, 3, 4, 5]")), "an array of 5 elements");
  EXPECT_EQ(describe(Json::object()), "an object");
  EXPECT_EQ(suggestion("positon", {"position", "look_at"}), "; did you mean \"position\"?");
  EXPECT_EQ(suggestion("zzz", {"position"}), "");
  // A name without its catalogue prefix, or with a word more: held, or holding.
  EXPECT_EQ(suggestion("BK7", {"N-BK7", "N-SF11", "F2", "fused_silica"}), "; did you mean \"N-BK7\"?");
  EXPECT_EQ(suggestion("silica", {"N-BK7", "N-SF11", "F2", "fused_silica"}), "; did you mean \"fused_silica\"?");
  EXPECT_EQ(suggestion("N-BK7 glass", {"N-BK7", "N-SF11"}), "; did you mean \"N-BK7\"?");
  // Two characters are too few to mean a match.
  EXPECT_EQ(suggestion("F", {"N-BK7", "F2"}), "; did you mean \"F2\"?");  // by edit distance, as before
  EXPECT_EQ(suggestion("ab", {"xxabyyzz"}), "");
  EXPECT_EQ(editDistance("D65", "d65"), 0u);
}

TEST(JsonFields, MessagesNameFilePointerAndValue) {
  Source c;
  c.file = "f.json";
  EXPECT_EQ(messageOf([&] { getInt(c, Json(2.5), "/a/b", 1, 9); }), "f.json: /a/b: must be an integer in 1..9 (got 2.5)");
  EXPECT_EQ(messageOf([&] { getPoint(c, Json::parse("[0, 0, 2e12]"), "/p", 1e12); }),
            "f.json: /p/2: must be a coordinate with magnitude <= 1e+12 m (got 2000000000000.0)");
  EXPECT_EQ(messageOf([&] { parseJson(c, "{\"a\": 1, \"a\": 2}"); }),
            "f.json: /a: duplicate key \"a\" (each key may appear only once per object)");
  c.note = " (light \"x\")";
  EXPECT_EQ(messageOf([&] { checkObject(c, Json::parse("{\"typ\": 1}"), "", {"type"}, "a light"); }),
            "f.json: /typ: unknown key \"typ\" in a light; did you mean \"type\"? (allowed keys: type) (light \"x\")");
  EXPECT_EQ(getDirection(c, Json::parse("[0, 0, -3]"), "/d"), glm::dvec3(0.0, 0.0, -1.0));
}

struct OwnError {
  std::string message;
};

TEST(JsonFields, SourceRaisesTheCallersException) {
  Source c;
  c.file = "f.json";
  c.raise = [](const std::string& message) { throw OwnError{message}; };
  try {
    getString(c, Json(3), "/name");
    FAIL() << "no error";
  } catch (const OwnError& e) {
    EXPECT_EQ(e.message, "f.json: /name: must be a string (got 3)");
  }
}

}  // namespace
}  // namespace spectrace::json_fields
