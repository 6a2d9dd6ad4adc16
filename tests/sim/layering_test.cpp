// The simulation core does no I/O: no source of libs/{core,nav,sim} may include files, clocks,
// sockets, or the io/net layers (GUIDE §2). The file-format libraries link only downward:
// motion → core; io (scenario loading) → core, nav, sim, common_ground, motion; recording → core, nav,
// sim, common_ground (never io, motion, hub or the network libraries), and it is the one SQLite layer:
// no other library or app includes sqlite3.h. Every library links only what docs/architecture.md's
// dependency diagram allows it (a new library must be added to that table here), includes only
// what it links, and only the network libraries include Boost.Asio.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <vector>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

TEST(Layering, SimulationLibrariesDoNoIo) {
  const std::regex forbidden(R"(#\s*include\s*[<"](fstream|chrono|iostream|sys/socket\.h|netinet/.*|boost/asio.*|throng/(io|recording|motion)/.*|throng/net/.*|sqlite3\.h)[>"])");
  // <cstdio> is allowed for snprintf formatting; printing or opening files is not.
  const std::regex io(R"(\b(fopen|printf|puts|fputs)\s*\(|std::(cout|cerr|clog)\b)");
  int checked = 0;
  for (const char* lib : {"core", "nav", "crowd", "common_ground", "sim"}) {
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

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Every library under libs/ and the throng libraries its CMake target links (throng::X).
std::map<std::string, std::set<std::string>> linkedLibraries() {
  std::map<std::string, std::set<std::string>> deps;
  const std::regex link(R"(target_link_libraries\s*\(\s*throng_(\w+)([^)]*)\))");
  const std::regex dep(R"(throng::(\w+))");
  for (const auto& dir : fs::directory_iterator(fs::path(THRONG_SOURCE_DIR) / "libs")) {
    if (!dir.is_directory()) continue;
    deps[dir.path().filename().string()];
    const std::string cmake = readFile(dir.path() / "CMakeLists.txt");
    for (auto m = std::sregex_iterator(cmake.begin(), cmake.end(), link); m != std::sregex_iterator(); ++m) {
      const std::string args = (*m)[2];
      for (auto d = std::sregex_iterator(args.begin(), args.end(), dep); d != std::sregex_iterator(); ++d) {
        deps[(*m)[1]].insert((*d)[1]);
      }
    }
  }
  return deps;
}

std::set<std::string> closure(const std::map<std::string, std::set<std::string>>& deps, const std::string& lib) {
  std::set<std::string> seen;
  std::vector<std::string> todo{lib};
  while (!todo.empty()) {
    const std::string l = todo.back();
    todo.pop_back();
    if (!seen.insert(l).second || !deps.count(l)) continue;
    for (const std::string& d : deps.at(l)) todo.push_back(d);
  }
  return seen;
}

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

// The dependency diagram of docs/architecture.md, enforced: a library's sources include public
// headers only of the libraries its CMake target links (directly or through them), and no
// library's CMake reaches into another library's private src/.
TEST(Layering, LibrariesIncludeOnlyWhatTheyLink) {
  const auto deps = linkedLibraries();
  ASSERT_GE(deps.size(), 10u);
  const std::regex include(R"(#\s*include\s*[<"]throng/(\w+)/)");
  int checked = 0;
  for (const auto& [lib, direct] : deps) {
    const std::set<std::string> allowed = closure(deps, lib);
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(THRONG_SOURCE_DIR) / "libs" / lib)) {
      const auto ext = entry.path().extension();
      if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".hpp" && ext != ".in")) continue;
      std::ifstream in(entry.path());
      std::string line;
      for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        std::smatch m;
        if (!std::regex_search(line, m, include) || allowed.count(m[1])) continue;
        ADD_FAILURE() << entry.path() << ":" << lineNo << ": library " << lib << " includes throng/" << m[1]
                      << " but its CMake target does not link throng::" << m[1];
      }
      ++checked;
    }
    const std::string cmake = readFile(fs::path(THRONG_SOURCE_DIR) / "libs" / lib / "CMakeLists.txt");
    const std::regex privateSrc(R"(libs/(\w+)/src)");
    for (auto m = std::sregex_iterator(cmake.begin(), cmake.end(), privateSrc); m != std::sregex_iterator(); ++m) {
      EXPECT_EQ((*m)[1], lib) << "libs/" << lib << "/CMakeLists.txt reaches into libs/" << (*m)[1] << "/src";
    }
  }
  EXPECT_GT(checked, 100);
}

// Apps and benchmarks use libraries through their public headers only.
TEST(Layering, AppsAndBenchesUseNoLibrarysPrivateSources) {
  const std::regex privateInclude(R"(#\s*include\s*"[^"]*(libs/\w+/src/|\.\./src/|\.\./\.\./libs/))");
  for (const char* dir : {"apps", "benches", "examples"}) {
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(THRONG_SOURCE_DIR) / dir)) {
      const auto ext = entry.path().extension();
      if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".hpp" && ext != ".c" && ext != ".txt")) continue;
      const std::string text = readFile(entry.path());
      EXPECT_FALSE(std::regex_search(text, privateInclude)) << entry.path() << " includes a library's private source";
      if (entry.path().filename() == "CMakeLists.txt") {
        // A path into libs/ on a line that is not a comment: sources or private includes of a library.
        const std::regex libsPath(R"((^|\n)[ \t]*[^#\n]*libs/)");
        EXPECT_FALSE(std::regex_search(text, libsPath)) << entry.path() << " names a library's sources directly";
      }
    }
  }
}

// docs/architecture.md shows every library (and names no library that does not exist).
TEST(Layering, TheArchitecturePageShowsEveryLibrary) {
  const std::string doc = readFile(fs::path(THRONG_SOURCE_DIR) / "docs" / "architecture.md");
  const auto deps = linkedLibraries();
  for (const auto& [lib, direct] : deps) {
    EXPECT_NE(doc.find("libs/" + lib + "/"), std::string::npos) << "docs/architecture.md does not show libs/" << lib << "/";
  }
  const std::regex named(R"(libs/(\w+)/)");
  for (auto m = std::sregex_iterator(doc.begin(), doc.end(), named); m != std::sregex_iterator(); ++m) {
    EXPECT_TRUE(deps.count((*m)[1])) << "docs/architecture.md names libs/" << (*m)[1] << "/, which does not exist";
  }
}

TEST(Layering, FileFormatLibrariesLinkOnlyDownward) {
  const std::vector<std::pair<const char*, std::set<std::string>>> allowed{
      {"motion", {"core", "motion"}},
      {"io", {"core", "nav", "sim", "common_ground", "motion", "io"}},
      {"recording", {"core", "nav", "sim", "common_ground", "recording"}},
  };
  for (const auto& [lib, may] : allowed) {
    const auto found = throngIncludes(lib);
    EXPECT_FALSE(found.empty()) << lib;
    for (const auto& [name, where] : found) EXPECT_TRUE(may.count(name)) << where;
  }
}

// docs/architecture.md's dependency diagram ("In words"), one row per library: what it uses. A
// library may link what it uses and what those use in turn, nothing else.
TEST(Layering, EveryLibraryLinksOnlyWhatTheDiagramAllows) {
  const std::map<std::string, std::set<std::string>> uses{
      {"core", {}},
      {"nav", {"core"}},
      {"crowd", {"core", "nav"}},
      {"common_ground", {"core", "nav"}},
      {"sim", {"core", "nav", "crowd", "common_ground"}},
      {"motion", {"core"}},
      {"io", {"sim", "common_ground", "motion"}},
      {"recording", {"sim", "common_ground"}},
      {"protocol", {"core"}},
      {"net", {}},
      {"transport", {"core", "protocol", "net"}},
      {"client", {"core", "protocol", "net"}},
      {"hub", {"io", "motion", "recording", "sim", "protocol"}},
      {"link", {"core"}},
      {"capi", {"io", "recording", "sim"}},
      {"dist", {"sim"}},
      {"bench", {"sim"}},
  };
  const auto deps = linkedLibraries();
  for (const auto& [lib, direct] : deps) {
    ASSERT_TRUE(uses.count(lib)) << "libs/" << lib << " is missing from the diagram's table in this test (and maybe from docs/architecture.md)";
    const std::set<std::string> allowed = closure(uses, lib);
    for (const std::string& d : direct) {
      EXPECT_TRUE(allowed.count(d)) << "libs/" << lib << " links throng::" << d << ", which the diagram does not let it use";
    }
  }
  for (const auto& [lib, used] : uses) EXPECT_TRUE(deps.count(lib)) << "the table names libs/" << lib << ", which does not exist";
}

TEST(Layering, OnlyTheNetworkLibrariesIncludeAsio) {
  const std::regex asio(R"(#\s*include\s*[<"](boost/asio|boost/beast|throng/net/))");
  int checked = 0;
  for (const char* top : {"libs", "apps"}) {
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(THRONG_SOURCE_DIR) / top)) {
      if (!entry.is_regular_file()) continue;
      const auto ext = entry.path().extension();
      if (ext != ".cpp" && ext != ".hpp" && ext != ".h") continue;
      const std::string path = entry.path().generic_string();
      if (path.find("/libs/transport/") != std::string::npos || path.find("/libs/client/") != std::string::npos ||
          path.find("/libs/net/") != std::string::npos) {
        continue;
      }
      std::ifstream in(entry.path());
      std::string line;
      for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        EXPECT_FALSE(std::regex_search(line, asio)) << entry.path() << ":" << lineNo << ": " << line;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
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
