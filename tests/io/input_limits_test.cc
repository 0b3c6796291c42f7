#include "io/input_limits.h"

#include <string>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

TEST(JsonNestingDepth, CountsBracketsOutsideStrings) {
  EXPECT_EQ(JsonNestingDepth(""), 0);
  EXPECT_EQ(JsonNestingDepth("1"), 0);
  EXPECT_EQ(JsonNestingDepth("{\"a\": [1, {\"b\": []}]}"), 4);
  // Brackets inside strings, also after an escaped quote, do not count.
  EXPECT_EQ(JsonNestingDepth("{\"[[[\\\"{{{\": 1}"), 1);
  // Unbalanced closers never make the depth negative.
  EXPECT_EQ(JsonNestingDepth("]]]]{"), 1);
}

TEST(JsonNestingDepth, StopsPastTheLimit) {
  const std::string deep = std::string(30000, '[') + std::string(30000, ']');
  EXPECT_EQ(JsonNestingDepth(deep), kMaxThirdPartyNesting + 1);
  EXPECT_EQ(JsonNestingDepth(deep, 10), 11);
  EXPECT_EQ(JsonNestingDepth(std::string(128, '[')), 128);
}

TEST(FbxBraceDepth, CountsBracesOutsideStringsAndComments) {
  EXPECT_EQ(FbxBraceDepth("; FBX 7.4.0 project file {{{{\nObjects: {\n Model: 1, \"M::{{\", \"\" {\n }\n}\n"), 2);
  // A quote does not run past its line: the next line's braces count again.
  EXPECT_EQ(FbxBraceDepth("A: \"open\n{ {\n}}"), 2);
  const std::string deep = std::string(30000, '{');
  EXPECT_EQ(FbxBraceDepth(deep), kMaxThirdPartyNesting + 1);
}

}  // namespace
}  // namespace mocapsolve
