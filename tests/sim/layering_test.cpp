// The simulation core does no I/O: no source of libs/{core,nav,sim} may include files, clocks,
// sockets, or the io/net layers (GUIDE §2).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace fs = std::filesystem;

TEST(Layering, SimulationLibrariesDoNoIo) {
  const std::regex forbidden(R"(#\s*include\s*[<"](fstream|chrono|iostream|sys/socket\.h|netinet/.*|boost/asio.*|throng/io/.*|throng/net/.*|sqlite3\.h)[>"])");
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
