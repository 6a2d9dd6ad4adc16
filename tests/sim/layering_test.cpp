// The simulation core does no I/O: no source of libs/{core,nav,sim} may include files, clocks,
// sockets, or the io/net layers (GUIDE §2). The file-format libraries link only downward:
// motion → core; io (scenario loading) → core, nav, sim, social, motion; recording → core, nav,
// sim, social (never io, motion, hub or the network libraries), and it is the one SQLite layer:
// no other library or app includes sqlite3.h.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

TEST(Layering, SimulationLibrariesDoNoIo) {
  const std::regex forbidden(R"(#\s*include\s*[<"](fstream|chrono|iostream|sys/socket\.h|netinet/.*|boost/asio.*|throng/(io|recording|motion)/.*|throng/net/.*|sqlite3\.h)[>"])");
  // <cstdio> is allowed for snprintf formatting; printing or opening files is not.
  const std::regex io(R"(\b(fopen|printf|puts|fputs)\s*\(|std::(cout|cerr|clog)\b)");
  int checked = 0;
  for (const char* lib : {"core", "nav", "crowd", "social", "sim"}) {
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(THRONG_SOURCE_DIR) / "libs" / lib)) {
      if (!entry.is_regular_file()) continue;
      const auto ext = entry.path().extension();
      if (ext != ".cpp" && ext != ".hpp") continue;
      std::ifstream in(entry.path());
      std::string line;
      int lineNo = 0;
      while (std::getline(in, line)) {
        ++lineNo;
        // assert.hpp prints a failed invariant before aborting: the one sanctioned use of <cstdio>.
        if (entry.path().filename() == "assert.hpp") continue;
        EXPECT_FALSE(std::regex_search(line, forbidden)) << entry.path() << ":" << lineNo << ": " << line;
        EXPECT_FALSE(std::regex_search(line, io)) << entry.path() << ":" << lineNo << ": " << line;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 10);
}

namespace {

/// The throng libraries whose headers `lib` includes ("throng/<name>/..."), with where each was seen.
std::vector<std::pair<std::string, std::string>> throngIncludes(const char* lib) {
  const std::regex include(R"(#\s*include\s*[<"]throng/([a-z_]+)/)");
  std::vector<std::pair<std::string, std::string>> found;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(THRONG_SOURCE_DIR) / "libs" / lib)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path());
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
      ++lineNo;
      std::smatch m;
      if (std::regex_search(line, m, include)) {
        found.emplace_back(m[1].str(), entry.path().string() + ":" + std::to_string(lineNo) + ": " + line);
      }
    }
  }
  return found;
}

}  // namespace

TEST(Layering, FileFormatLibrariesLinkOnlyDownward) {
  const std::vector<std::pair<const char*, std::set<std::string>>> allowed{
      {"motion", {"core", "motion"}},
      {"io", {"core", "nav", "sim", "social", "motion", "io"}},
      {"recording", {"core", "nav", "sim", "social", "recording"}},
  };
  for (const auto& [lib, may] : allowed) {
    const auto found = throngIncludes(lib);
    EXPECT_FALSE(found.empty()) << lib;
    for (const auto& [name, where] : found) EXPECT_TRUE(may.count(name)) << where;
  }
}

TEST(Layering, OnlyTheRecordingLibraryOpensSqlite) {
  const std::regex sqlite(R"(#\s*include\s*[<"]sqlite3\.h[>"])");
  int checked = 0;
  for (const char* top : {"libs", "apps"}) {
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(THRONG_SOURCE_DIR) / top)) {
      if (!entry.is_regular_file()) continue;
      const auto ext = entry.path().extension();
      if (ext != ".cpp" && ext != ".hpp" && ext != ".h") continue;
      if (entry.path().string().find("/libs/recording/") != std::string::npos) continue;
      std::ifstream in(entry.path());
      std::string line;
      int lineNo = 0;
      while (std::getline(in, line)) {
        ++lineNo;
        EXPECT_FALSE(std::regex_search(line, sqlite)) << entry.path() << ":" << lineNo << ": " << line;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}
