// Helpers shared by the scenario loader tests: load text without reachability, find diagnostics.
#pragma once
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "throng/io/scenario_loader.hpp"

namespace throng::io::test {

/// 1-based line:column of the `nth` occurrence of `needle` in `text` (ASCII: columns count bytes).
inline std::pair<int, int> posOf(const std::string& text, const std::string& needle, std::size_t nth = 0) {
  std::size_t at = text.find(needle);
  for (std::size_t k = 0; k < nth && at != std::string::npos; ++k) at = text.find(needle, at + 1);
  EXPECT_NE(at, std::string::npos) << needle;
  int line = 1, col = 1;
  for (std::size_t i = 0; i < at && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

/// The diagnostic points at the `nth` occurrence of `needle` in `text`, in file `source`.
inline void expectAt(const core::Diagnostic& d, const std::string& text, const std::string& needle, std::size_t nth = 0,
                     const std::string& source = "t.json") {
  const auto [line, col] = posOf(text, needle, nth);
  EXPECT_EQ(d.source, source);
  EXPECT_EQ(d.line, line) << d.format();
  EXPECT_EQ(d.column, col) << d.format();
}

inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

inline core::Result<LoadedScenario> load(const std::string& text, bool reachability = false) {
  return parseScenario(text, "t.json", LoadOptions{reachability});
}

/// The diagnostics for `text`, which must fail to load.
inline core::Diagnostics errorsOf(const std::string& text, bool reachability = false) {
  auto r = load(text, reachability);
  EXPECT_FALSE(r.ok()) << "expected errors for:\n" << text;
  return r.ok() ? core::Diagnostics{} : r.errors();
}

/// The one diagnostic at `pointer`; fails the test when there is none.
inline core::Diagnostic at(const core::Diagnostics& ds, const std::string& pointer) {
  for (const auto& d : ds) {
    if (d.pointer == pointer) return d;
  }
  ADD_FAILURE() << "no diagnostic at " << pointer << "; got:\n" << core::formatAll(ds);
  return {};
}

/// The bottleneck example of docs/scenario-format.md, one line per key (line numbers matter).
inline const char* kBottleneck = R"({
  "format": "throng/1",
  "name": "bottleneck",
  "seed": 7,
  "duration": 300,
  "walkable":  [ [[0,0],[20,0],[20,10],[0,10]] ],
  "obstacles": [ [[9,0],[10,0],[10,4.5],[9,4.5]], [[9,5.5],[10,5.5],[10,10],[9,10]] ],
  "points": [
    {"id": "gap",  "kind": "interest", "position": [9.5, 5], "radius": 0.5},
    {"id": "exit", "kind": "exit", "polygon": [[19,4],[20,4],[20,6],[19,6]]}
  ],
  "populations": [
    {"id": "crowd", "groups": 100, "size": 1, "spawn": {"polygon": [[1,1],[8,1],[8,9],[1,9]]},
     "goals": ["gap", "exit"], "speed": {"mean": 1.34, "sd": 0.26}, "radius": 0.2}
  ]
}
)";

/// kBottleneck with `from` replaced by `to` (exactly once).
inline std::string edit(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

}  // namespace throng::io::test
