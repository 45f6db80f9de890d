// readObjText's reading in parts (obj_text.h: readObjTextInParts): the
// same vertices, faces and first fault as one reader going through the
// whole text, wherever the text is split.
#include "shapes/obj_text.h"

#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace spectrace {
namespace {

// One reader over the whole text: readObjTextInParts with no split.
ObjText readWhole(std::string_view text) { return readObjTextInParts(text, {}); }

void expectSame(const ObjText& got, const ObjText& expected, const std::string& where) {
  ASSERT_EQ(got.fault.has_value(), expected.fault.has_value()) << where;
  if (expected.fault) {
    EXPECT_EQ(got.fault->line, expected.fault->line) << where;
    EXPECT_EQ(got.fault->token, expected.fault->token) << where;
    EXPECT_EQ(got.fault->what, expected.fault->what) << where;
    return;
  }
  EXPECT_EQ(got.vertices, expected.vertices) << where;
  EXPECT_EQ(got.corners, expected.corners) << where;
  EXPECT_EQ(got.cornerCounts, expected.cornerCounts) << where;
}

// The offsets just after each "\n" but the last.
std::vector<size_t> lineStarts(std::string_view text) {
  std::vector<size_t> starts;
  for (size_t i = text.find('\n'); i != std::string_view::npos && i + 1 < text.size(); i = text.find('\n', i + 1))
    starts.push_back(i + 1);
  return starts;
}

// Texts whose reading depends on what came before: negative indices that
// reach back across a split, vertices after faces, faults early and late
// (the first in the file must be reported), an index beyond the file's
// vertices (known only at the end), line ends of every kind.
const std::vector<std::string> kTexts = {
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf -1 -2 -3\nf -4 -3 -1\n",
    "# a comment\nv 0 0 0\r\nv 1 0 0\r\nf 1 2 3\r\nv 0 1 0\r\nf -3 -2 -1\r\nv 1 1 1\rf -1 -2 -3 -4\rl 1 2\np -1\n",
    "v 0 0 0 1\nv 1 0 0 0.5 0.5 0.5\nvt 0 0\nvn 0 0 1\nv 0 1 0\nf 1/1/1 2//1 3/1\ng group\nf -3/1 -2 -1//1\n",
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 nan\nv 1 1 1\nf 1 2 0\n",
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3\nf -4 1 2\nv 1 1 1\n",
    "v 0 0 0\nv 1 0 0\nf 1 2 9\nv 0 1 0\nf 1 2 3\nf 1 2 7\n",
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 1e999 0 0\nf 1 2 3\n",
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1 2 3\n",
    "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\nf 1 2 3 x\n",
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv\n",
    "v 0 0 0\n  v 1 0 0 # indented\n\tv 0 1 0\nf 1 2 3 # the last line has no end",
};

TEST(ObjTextInParts, EveryOneSplitReadsAsTheWholeText) {
  int splits = 0, faulty = 0;
  for (size_t t = 0; t < kTexts.size(); ++t) {
    const std::string& text = kTexts[t];
    const ObjText whole = readWhole(text);
    faulty += whole.fault ? 1 : 0;
    for (size_t split : lineStarts(text)) {
      ++splits;
      ASSERT_NO_FATAL_FAILURE(
          expectSame(readObjTextInParts(text, {split}), whole, "text " + std::to_string(t) + " split at " +
                                                                   std::to_string(split)));
    }
  }
  EXPECT_GT(splits, 50);
  EXPECT_EQ(faulty, 7) << "the texts' faults, as one reader finds them";
}

TEST(ObjTextInParts, EveryTwoSplitsReadAsTheWholeText) {
  for (size_t t = 0; t < kTexts.size(); ++t) {
    const std::string& text = kTexts[t];
    const ObjText whole = readWhole(text);
    const std::vector<size_t> starts = lineStarts(text);
    for (size_t i = 0; i < starts.size(); ++i)
      for (size_t j = i + 1; j < starts.size(); ++j)
        ASSERT_NO_FATAL_FAILURE(expectSame(readObjTextInParts(text, {starts[i], starts[j]}), whole,
                                           "text " + std::to_string(t) + " split at " + std::to_string(starts[i]) +
                                               " and " + std::to_string(starts[j])));
  }
}

// A text large enough that readObjText splits it: a grid's vertices, then
// its faces, half of them by negative indices, as exporters write them.
std::string gridText(int n) {
  std::string text = "# grid\n";
  char line[96];
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", x / double(n), y / double(n), 0.25 * x * y / n / n);
      text += line;
    }
  const int vertices = (n + 1) * (n + 1);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x + 1, b = a + 1, c = a + n + 1, d = c + 1;
      if ((x + y) % 2 == 0)
        std::snprintf(line, sizeof line, "f %d %d %d %d\n", a, b, d, c);
      else
        std::snprintf(line, sizeof line, "f %d %d %d\n", a - vertices - 1, b - vertices - 1, d - vertices - 1);
      text += line;
    }
  return text;
}

TEST(ObjTextInParts, ALargeTextIsReadAsOneReaderReadsIt) {
  const std::string text = gridText(300);
  ASSERT_GT(text.size(), size_t(4) << 20) << "large enough to be split";
  const ObjText whole = readWhole(text);
  ASSERT_FALSE(whole.fault);
  EXPECT_EQ(whole.vertices.size(), 301u * 301u);
  EXPECT_EQ(whole.cornerCounts.size(), 300u * 300u);
  expectSame(readObjText(text), whole, "readObjText");
  // A fault near the end: the same message, with the whole file's line.
  const std::string faulty = text + "f 1 2 -99999999\n";
  const ObjText wholeFaulty = readWhole(faulty);
  ASSERT_TRUE(wholeFaulty.fault);
  expectSame(readObjText(faulty), wholeFaulty, "readObjText, a fault at the end");
}

}  // namespace
}  // namespace spectrace
