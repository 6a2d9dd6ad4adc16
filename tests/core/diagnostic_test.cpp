// Tests for libs/core/src/diagnostic.cpp: the one-line format and "did you mean" matching.
#include "throng/core/diagnostic.hpp"
#include "throng/core/text.hpp"

#include <gtest/gtest.h>

using throng::core::Diagnostic;
namespace core = throng::core;

TEST(Diagnostic, FormatsEveryPart) {
  const Diagnostic d{"mall.json", 14, 7, "/populations/0/goals/1", "unknown point \"exitt\"",
                     "an id from /points", "did you mean \"exit\"?"};
  EXPECT_EQ(d.format(),
            "mall.json:14:7 /populations/0/goals/1: unknown point \"exitt\"; expected an id from /points "
            "(did you mean \"exit\"?)");
}

TEST(Diagnostic, OmitsMissingParts) {
  Diagnostic d;
  d.source = "a.json";
  d.what = "cannot open file";
  EXPECT_EQ(d.format(), "a.json: cannot open file");
  d.line = 3;
  EXPECT_EQ(d.format(), "a.json:3: cannot open file");
  d.column = 9;
  d.expected = "a number";
  EXPECT_EQ(d.format(), "a.json:3:9: cannot open file; expected a number");
  d.pointer = "/seed";
  d.hint = "h";
  EXPECT_EQ(d.format(), "a.json:3:9 /seed: cannot open file; expected a number (h)");
}

TEST(Diagnostic, FormatAllJoinsLines) {
  core::Diagnostics ds{{"f", 1, 1, "", "a", "", ""}, {"f", 2, 1, "", "b", "", ""}};
  EXPECT_EQ(core::formatAll(ds), "f:1:1: a\nf:2:1: b");
  EXPECT_EQ(core::formatAll({}), "");
}

TEST(Diagnostic, ClosestMatchFindsTypos) {
  const std::vector<std::string> keys{"populations", "points", "obstacles", "walkable", "seed"};
  EXPECT_EQ(core::closestMatch("populatoins", keys), "populations");
  EXPECT_EQ(core::closestMatch("obstacle", keys), "obstacles");
  EXPECT_EQ(core::closestMatch("Seed", keys), "seed");
  EXPECT_EQ(core::closestMatch("exitt", {"gap", "exit"}), "exit");
  EXPECT_EQ(core::closestMatch("zzzzzzzz", keys), "");
  EXPECT_EQ(core::closestMatch("ab", {"xy"}), "");  // sharing nothing is no typo
  EXPECT_EQ(core::closestMatch("anything", {}), "");
}

TEST(Diagnostic, PrintableEscapesControlsAndBadUtf8) {
  EXPECT_EQ(core::printable("plain é €"), "plain é €");
  EXPECT_EQ(core::printable("a\nb\tc\rd\x07" "e\x7f"), "a\\nb\\tc\\rd\\u0007e\\u007F");
  EXPECT_EQ(core::printable("\x1b[31mred"), "\\u001B[31mred");  // no terminal escapes
  EXPECT_EQ(core::printable("\xC2\x9B" "1m"), "\\u009B1m");       // C1 control (CSI)
  EXPECT_EQ(core::printable("ab\xFF\xC3"), "ab\\xFF\\xC3");
  EXPECT_EQ(core::printable("\xED\xA0\x80"), "\\xED\\xA0\\x80");  // surrogate half
  EXPECT_TRUE(core::isUtf8(core::printable("x\xF4\x90\x80\x80y")));
}

TEST(Diagnostic, PrintableCapsAtACharacterBoundary) {
  std::string text;
  for (int i = 0; i < 100; ++i) text += "\xC3\xA9";  // é, two bytes each
  const std::string shown = core::printable(text, 80);
  EXPECT_TRUE(core::isUtf8(shown));
  EXPECT_EQ(shown.size(), 80u * 2 + 3);
  EXPECT_EQ(shown.substr(shown.size() - 3), "...");
  EXPECT_EQ(core::printable("short", 80), "short");
  EXPECT_EQ(core::printable("exactly", 7), "exactly");
}

TEST(Diagnostic, FormatIsOneLineOfUtf8) {
  core::Diagnostic d{"f\n.json", 1, 2, "/na\tme", "unknown point \"a\nb\xFF\"", "an id", "did you mean \"\x1b\"?"};
  const std::string line = d.format();
  EXPECT_EQ(line, "f\\n.json:1:2 /na\\tme: unknown point \"a\\nb\\xFF\"; expected an id (did you mean \"\\u001B\"?)");
  EXPECT_TRUE(core::isUtf8(line));
}
