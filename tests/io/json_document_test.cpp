// Tests for libs/io/src/json_document.cpp: values, pointer → line:column positions, escapes.
#include "json_document.hpp"
#include "throng/core/text.hpp"

#include <gtest/gtest.h>

using throng::io::JsonDocument;

TEST(JsonDocument, ValuesAndPositions) {
  const std::string text = "{\n  \"a\": [1, -2, 3.5e1],\n  \"b~/c\": {\"d\": \"\\u00e9\\ud83d\\ude00\"},\n\t\"e\": null\n}";
  auto r = JsonDocument::parse(text, "x.json");
  ASSERT_TRUE(r.ok()) << throng::core::formatAll(r.errors());
  const JsonDocument& doc = r.value();
  EXPECT_EQ(doc.root()["a"][0].get<int>(), 1);
  EXPECT_EQ(doc.root()["a"][1].get<int>(), -2);
  EXPECT_DOUBLE_EQ(doc.root()["a"][2].get<double>(), 35.0);
  EXPECT_EQ(doc.root()["b~/c"]["d"].get<std::string>(), "\xC3\xA9\xF0\x9F\x98\x80");
  EXPECT_TRUE(doc.root()["e"].is_null());
  EXPECT_EQ(doc.position("").line, 1);
  EXPECT_EQ(doc.position("/a").line, 2);
  EXPECT_EQ(doc.position("/a").column, 8);
  EXPECT_EQ(doc.keyPosition("/a").column, 3);
  EXPECT_EQ(doc.position("/a/1").column, 12);
  EXPECT_EQ(doc.position("/b~0~1c/d").line, 3);
  EXPECT_EQ(doc.position("/b~0~1c/d").column, 17);
  EXPECT_EQ(doc.keyPosition("/e").line, 4);
  EXPECT_EQ(doc.keyPosition("/e").column, 2);  // a tab counts as one column
  // Unknown pointers fall back to the nearest ancestor.
  EXPECT_EQ(doc.position("/a/7").column, 8);
  const auto d = doc.diagnostic("/a/1", "bad", "good");
  EXPECT_EQ(d.format(), "x.json:2:12 /a/1: bad; expected good");
}

TEST(JsonDocument, ColumnsCountCodePoints) {
  auto r = JsonDocument::parse("{\"\xC3\xA9\xC3\xA9\": x}", "u.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors()[0].column, 8);
}

TEST(JsonDocument, RejectsBadNumbersAndEscapes) {
  for (const char* bad : {"[01]", "[1.]", "[-]", "[1e999]", "[\"\\x\"]", "[\"\\ud800\"]", "[tru]", "[1] 2", "{\"a\" 1}"}) {
    auto r = JsonDocument::parse(bad, "b.json");
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.errors().size(), 1u);
    EXPECT_EQ(r.errors()[0].line, 1) << bad;
    EXPECT_GE(r.errors()[0].column, 2) << bad;
  }
  auto big = JsonDocument::parse("[18446744073709551615, -9223372036854775808, 1e300]", "n.json");
  ASSERT_TRUE(big.ok());
  EXPECT_EQ(big.value().root()[0].get<std::uint64_t>(), 18446744073709551615ull);
  EXPECT_EQ(big.value().root()[1].get<std::int64_t>(), INT64_MIN);
}

// --- hostile input (issue 15, items 6, 10): linear time, UTF-8, nesting ---

namespace {

/// {"k0": 0, "k1": 1, ...} on one line per key.
std::string manyKeys(std::size_t n, const std::string& extra = {}) {
  std::string text = "{\n";
  for (std::size_t i = 0; i < n; ++i) text += "\"k" + std::to_string(i) + "\": " + std::to_string(i) + ",\n";
  return text + extra + "\"last\": true\n}";
}

}  // namespace

TEST(JsonDocument, ManyKeysParseAndLocateInLinearTime) {
  // 300,000 keys (~4 MiB): every key's position is found and every lookup is answered from the
  // object's key index; the old reader scanned every key seen for each new one (hours here).
  const std::size_t n = 300000;
  auto r = JsonDocument::parse(manyKeys(n), "many.json");
  ASSERT_TRUE(r.ok()) << throng::core::formatAll(r.errors());
  const JsonDocument& doc = r.value();
  EXPECT_EQ(doc.root().size(), n + 1);
  for (std::size_t i = 0; i < n; i += 997) {
    EXPECT_EQ(doc.keyPosition("/k" + std::to_string(i)).line, static_cast<int>(i) + 2);
    EXPECT_EQ(doc.position("/k" + std::to_string(i)).column, static_cast<int>(std::to_string(i).size()) + 6);
  }
  EXPECT_EQ(doc.keyPosition("/last").line, static_cast<int>(n) + 2);
  EXPECT_EQ(doc.position("/nothere").line, 1);  // unknown key: the object's own position
}

TEST(JsonDocument, DuplicateKeyFoundInABigObject) {
  auto r = JsonDocument::parse(manyKeys(50000, "\"k123\": 5,\n"), "dup.json");
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.errors().size(), 1u);
  EXPECT_EQ(r.errors()[0].line, 50002);
  EXPECT_EQ(r.errors()[0].column, 1);
  EXPECT_EQ(r.errors()[0].pointer, "/k123");
  EXPECT_EQ(r.errors()[0].what, "duplicate key \"k123\"");
  // And in a small object (scanned, not indexed).
  auto small = JsonDocument::parse("{\"a\": {\"x\": 1, \"y\": 2, \"x\": 3}}", "s.json");
  ASSERT_FALSE(small.ok());
  EXPECT_EQ(small.errors()[0].pointer, "/a/x");
  EXPECT_EQ(small.errors()[0].column, 24);
}

TEST(JsonDocument, StringsMustBeUtf8) {
  struct Case {
    std::string text;
    int column;
  };
  const std::vector<Case> cases = {
      {"{\"name\": \"ab\xFF\"}", 13},          // never valid in UTF-8
      {"{\"name\": \"\xC3\x28\"}", 11},        // lead byte without its continuation
      {"{\"name\": \"\xC0\xAF\"}", 11},        // overlong "/"
      {"{\"name\": \"\xED\xA0\x80\"}", 11},    // UTF-16 surrogate half
      {"{\"name\": \"\xF4\x90\x80\x80\"}", 11}, // beyond U+10FFFF
      {"{\"\x80\": 1}", 3},                     // a key too
      {"[\"\xE2\x82", 3},                       // cut short by the end of the text
  };
  for (const Case& c : cases) {
    auto r = JsonDocument::parse(c.text, "u.json");
    ASSERT_FALSE(r.ok()) << c.text;
    ASSERT_EQ(r.errors().size(), 1u);
    const auto& d = r.errors()[0];
    EXPECT_EQ(d.line, 1) << c.text;
    EXPECT_EQ(d.column, c.column) << c.text;
    EXPECT_NE(d.what.find("is not UTF-8"), std::string::npos) << d.format();
    EXPECT_EQ(d.expected.rfind("UTF-8 text", 0), 0u) << d.format();
    EXPECT_TRUE(throng::core::isUtf8(d.format())) << d.format();
  }
  auto ok = JsonDocument::parse("{\"name\": \"\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80 \\u0007\"}", "ok.json");
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(ok.value().root()["name"].get<std::string>(), "\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80 \x07");
}

TEST(JsonDocument, NestingIsBoundedWithALocatedMessage) {
  const int max = JsonDocument::kMaxDepth;
  auto deep = JsonDocument::parse(std::string(max, '[') + std::string(max, ']'), "d.json");
  EXPECT_TRUE(deep.ok());
  auto tooDeep = JsonDocument::parse("{\"a\":\n" + std::string(max + 5, '[') + std::string(max + 5, ']') + "}", "d.json");
  ASSERT_FALSE(tooDeep.ok());
  const auto& d = tooDeep.errors()[0];
  EXPECT_EQ(d.line, 2);
  EXPECT_EQ(d.column, max);  // the first array one level too deep
  EXPECT_EQ(d.pointer, "/a" + [&] {
    std::string p;
    for (int i = 0; i < max - 1; ++i) p += "/0";
    return p;
  }());
  EXPECT_NE(d.what.find("nesting deeper than 64 levels"), std::string::npos) << d.format();
}
