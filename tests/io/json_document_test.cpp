// Tests for libs/io/src/json_document.cpp: values, pointer → line:column positions, escapes.
#include "json_document.hpp"

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
