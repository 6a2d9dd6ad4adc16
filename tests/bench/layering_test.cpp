// libs/bench sits on the simulation only: its sources include throng headers of core, nav, sim and
// bench alone (no io, no network, nothing of apps/ or benches/), so the CLI and the benchmarks can
// both link it; and no other library includes it (only apps/throng, benches/ and tests do).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace fs = std::filesystem;

namespace {

template <class Check>
int forEachInclude(const fs::path& dir, Check check) {
  const std::regex include(R"(#\s*include\s*[<"]([^>"]+)[>"])");
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const auto ext = entry.path().extension();
    if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".hpp")) continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
      std::smatch m;
      if (std::regex_search(line, m, include)) check(entry.path().string() + ":" + std::to_string(lineNo), m[1].str());
    }
  }
  return files;
}

TEST(BenchLayering, IncludesOnlyTheSimulationLibraries) {
  const std::regex allowed(R"(throng/(core|nav|sim|bench)/.*)");
  const int files = forEachInclude(fs::path(THRONG_SOURCE_DIR) / "libs" / "bench",
                                   [&](const std::string& where, const std::string& header) {
                                     if (!header.starts_with("throng/")) return;  // std, fmt, Detour
                                     EXPECT_TRUE(std::regex_match(header, allowed)) << where << ": " << header;
                                   });
  EXPECT_GE(files, 4);
}

TEST(BenchLayering, NoLibraryIncludesIt) {
  int files = 0;
  for (const auto& lib : fs::directory_iterator(fs::path(THRONG_SOURCE_DIR) / "libs")) {
    if (!lib.is_directory() || lib.path().filename() == "bench") continue;
    files += forEachInclude(lib.path(), [&](const std::string& where, const std::string& header) {
      EXPECT_FALSE(header.starts_with("throng/bench/")) << where << ": " << header;
    });
  }
  EXPECT_GT(files, 100);
}

}  // namespace
