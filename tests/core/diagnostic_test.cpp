// Tests for libs/core/src/diagnostic.cpp: the one-line format and "did you mean" matching.
#include "throng/core/diagnostic.hpp"

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
