// JSON reader: every value kind, escapes, number edge cases, exact error messages, the
// depth limit, and a seeded fuzz over random bytes and mutated documents (no crash).
#include "io/json_reader.h"

#include <cmath>
#include <random>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/json_writer.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

JsonNode Parse(const std::string& text) {
  JsonNode node;
  const Status status = ParseJson(text, "t.json", &node);
  EXPECT_TRUE(status.ok()) << status.message();
  return node;
}

std::string Error(const std::string& text, const JsonReadOptions& options = {}) {
  JsonNode node;
  const Status status = ParseJson(text, "t.json", &node, options);
  EXPECT_FALSE(status.ok()) << "accepted: " << text;
  return status.message();
}

TEST(JsonReader, Scalars) {
  EXPECT_TRUE(Parse("null").is_null());
  EXPECT_TRUE(Parse(" true ").boolean);
  EXPECT_FALSE(Parse("false").boolean);
  EXPECT_TRUE(Parse("false").is_bool());
  EXPECT_EQ(Parse("\"abc\"").string, "abc");
  EXPECT_EQ(Parse("0").number, 0.0);
  EXPECT_EQ(Parse("-0").number, 0.0);
  EXPECT_EQ(Parse("12").number, 12.0);
  EXPECT_EQ(Parse("-1.5e3").number, -1500.0);
  EXPECT_EQ(Parse("2E-2").number, 0.02);
  EXPECT_EQ(Parse("1e+2").number, 100.0);
  EXPECT_EQ(Parse("0.1").number, 0.1);
  EXPECT_EQ(Parse("1e-400").number, 0.0);  // Underflow to zero is not an error.
  EXPECT_EQ(Parse("\xEF\xBB\xBF[]").items.size(), 0u);  // UTF-8 BOM.
}

TEST(JsonReader, NumbersRoundTripThroughTheWriter) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> value(-1e6, 1e6);
  for (int i = 0; i < 1000; ++i) {
    const double x = value(rng) * std::pow(10.0, static_cast<int>(rng() % 30) - 15);
    EXPECT_EQ(Parse(JsonValue(x).text()).number, x);
  }
}

TEST(JsonReader, StringEscapes) {
  EXPECT_EQ(Parse(R"("a\"b\\c\/d\be\ff\ng\rh\ti")").string, "a\"b\\c/d\be\ff\ng\rh\ti");
  EXPECT_EQ(Parse(R"("\u0041\u00e9\u20AC")").string, "A\xC3\xA9\xE2\x82\xAC");  // A é €
  EXPECT_EQ(Parse(R"("\ud83d\ude00")").string, "\xF0\x9F\x98\x80");         // U+1F600
  EXPECT_EQ(Parse("\"caf\xC3\xA9\"").string, "caf\xC3\xA9");                 // Raw UTF-8 kept.
  // The writer's quoting reads back.
  const std::string tricky = std::string("tab\t quote\" back\\ nl\n ctl\x01 end");
  EXPECT_EQ(Parse(JsonQuote(tricky)).string, tricky);
}

TEST(JsonReader, ObjectsKeepKeyOrderAndPositions) {
  const JsonNode root = Parse("{\n  \"b\": 1,\n  \"a\": [true, null, {\"x\": \"y\"}],\n  \"c\": {}\n}");
  ASSERT_TRUE(root.is_object());
  ASSERT_EQ(root.members.size(), 3u);
  EXPECT_EQ(root.members[0].first, "b");
  EXPECT_EQ(root.members[1].first, "a");
  EXPECT_EQ(root.members[2].first, "c");
  const JsonNode* a = root.Find("a");
  ASSERT_NE(a, nullptr);
  ASSERT_EQ(a->items.size(), 3u);
  EXPECT_TRUE(a->items[1].is_null());
  EXPECT_EQ(a->items[2].Find("x")->string, "y");
  EXPECT_EQ(root.Find("missing"), nullptr);
  EXPECT_EQ(a->items[0].Find("x"), nullptr);  // Not an object.
  // Positions: "a"'s value starts at line 3, column 8.
  EXPECT_EQ(a->line, 3);
  EXPECT_EQ(a->column, 8);
  EXPECT_EQ(a->items[2].Where("f.json"), "f.json:3:21");
  EXPECT_TRUE(root.Find("c")->is_object());
}

TEST(JsonReader, ErrorMessagesNameFileLineColumnAndToken) {
  EXPECT_EQ(Error("{\"a\": 1,\n \"b\" 2}"), "t.json:2:6: expected ':', got '2'");
  EXPECT_EQ(Error("[1, 2"), "t.json:1:6: expected ',' or ']', got end of file");
  EXPECT_EQ(Error("{\"a\": 1 \"b\": 2}"), "t.json:1:9: expected ',' or '}', got '\"b\"'");
  EXPECT_EQ(Error("[tru]"), "t.json:1:2: expected a value, got 'tru'");
  EXPECT_EQ(Error(""), "t.json:1:1: expected a value, got end of file");
  EXPECT_EQ(Error("[1] x"), "t.json:1:5: expected end of file, got 'x'");
  EXPECT_EQ(Error("{\"a\": 1, \"a\": 2}"),
            "t.json:1:10: expected a key not used before in this object, got '\"a\"'");
  EXPECT_EQ(Error("[\x01]"), "t.json:1:2: expected a value, got '\\x01'");
}

TEST(JsonReader, RejectsWhatJsonDoesNotAllow) {
  for (const char* text :
       {"[1,]", "{\"a\":1,}", "[01]", "[1.]", "[.5]", "[1e]", "[+1]", "[NaN]", "[Infinity]",
        "['a']", "[1 2]", "{a: 1}", "// c\n[]", "[\"a\nb\"]", "[\"\\x\"]", "[\"\\u12\"]",
        "[\"\\udc00\"]", "[\"\\ud800\"]", "[\"\\ud800\\u0041\"]", "[1e999]", "[-1e999]",
        "nul", "truex", "[", "{", "\"abc", "]", "{\"a\"}", "{1: 2}", "[\"tab\there\"]"}) {
    SCOPED_TRACE(text);
    Error(text);
  }
  EXPECT_THAT(Error("[1e999]"), HasSubstr("within double range"));
}

TEST(JsonReader, DepthLimit) {
  JsonReadOptions options;
  options.max_depth = 5;
  JsonNode node;
  EXPECT_TRUE(ParseJson("[[[[[1]]]]]", "t.json", &node, options).ok());
  EXPECT_THAT(Error("[[[[[[1]]]]]]", options), HasSubstr("at most 5 nested"));
  EXPECT_THAT(Error("{\"a\":{\"a\":{\"a\":{\"a\":{\"a\":{\"a\":1}}}}}}", options), HasSubstr("t.json:1:"));
  // The default limit stops a deep bomb long before the stack would overflow.
  EXPECT_THAT(Error(std::string(100000, '[')), HasSubstr("nested"));
  EXPECT_THAT(Error(std::string(100000, '{')), HasSubstr("expected"));
}

TEST(JsonReader, BigObjectsAndArraysParseInLinearTime) {
  // 200k keys: a quadratic duplicate-key check would take minutes here.
  std::string text = "{";
  for (int i = 0; i < 200000; ++i) text += (i ? ",\"k" : "\"k") + std::to_string(i) + "\": " + std::to_string(i);
  JsonNode node;
  ASSERT_TRUE(ParseJson(text + "}", "big.json", &node).ok());
  EXPECT_EQ(node.members.size(), 200000u);
  EXPECT_EQ(node.members.back().second.number, 199999.0);
  EXPECT_THAT(Error(text + ", \"k7\": 0}"), HasSubstr("a key not used before"));
}

TEST(JsonReader, ReadJsonFileNamesTheMissingPath) {
  JsonNode node;
  const Status status = ReadJsonFile("/nonexistent/dir/set.json", &node);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("/nonexistent/dir/set.json"));
}

TEST(JsonReader, FuzzNeverCrashes) {
  // Random bytes, and single-byte mutations / truncations of a valid document: every
  // input gives a tree or an error (ASan builds check the memory side).
  const std::string valid =
      "{\"format\": \"x\", \"v\": [1, -2.5e-3, true, false, null, \"s\\u00e9\\n\"], \"o\": {\"k\": []}}";
  std::mt19937 rng(7);
  const std::string alphabet = "{}[],:\"\\u0123456789abcdefnulltrue-+.eE \n\t\x01\xff";
  int accepted = 0;
  for (int i = 0; i < 20000; ++i) {
    std::string text;
    if (i % 2 == 0) {
      const int n = static_cast<int>(rng() % 40);
      for (int k = 0; k < n; ++k) text += alphabet[rng() % alphabet.size()];
    } else {
      text = valid;
      const int edits = 1 + static_cast<int>(rng() % 3);
      for (int k = 0; k < edits; ++k) {
        const size_t at = rng() % text.size();
        switch (rng() % 3) {
          case 0: text[at] = alphabet[rng() % alphabet.size()]; break;
          case 1: text.erase(at, 1); break;
          default: text = text.substr(0, at); break;
        }
        if (text.empty()) break;
      }
    }
    JsonNode node;
    const Status status = ParseJson(text, "fuzz.json", &node);
    if (status.ok()) {
      ++accepted;
    } else {
      EXPECT_EQ(status.message().find('\n'), std::string::npos) << "multi-line error";
      EXPECT_EQ(status.message().rfind("fuzz.json:", 0), 0u) << status.message();
    }
  }
  EXPECT_GT(accepted, 0);  // Some mutations stay valid (e.g. a digit for a digit).
}

}  // namespace
}  // namespace mocapsolve
