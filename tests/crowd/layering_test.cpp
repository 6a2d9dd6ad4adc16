// libs/crowd is simulation code: it may use core and nav only — no io/net/sim headers, files,
// clocks or sockets (GUIDE §2; tests/sim/layering_test.cpp checks core, nav and sim).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace fs = std::filesystem;

TEST(CrowdLayering, IncludesOnlyCoreAndNav) {
  const std::regex forbidden(
      R"(#\s*include\s*[<"](fstream|chrono|iostream|thread|random|sys/socket\.h|netinet/.*|sqlite3\.h|throng/(io|net|sim|social)/.*)[>"])");
  const std::regex io(R"(\b(fopen|printf|puts|fputs|std::cout|std::cerr|std::clog|std::random_device)\b)");
  int checked = 0;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(THRONG_SOURCE_DIR) / "libs" / "crowd")) {
    if (!entry.is_regular_file()) continue;
    const auto ext = entry.path().extension();
    if (ext != ".cpp" && ext != ".hpp") continue;
    std::ifstream in(entry.path());
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
      ++lineNo;
      EXPECT_FALSE(std::regex_search(line, forbidden)) << entry.path() << ":" << lineNo << ": " << line;
      EXPECT_FALSE(std::regex_search(line, io)) << entry.path() << ":" << lineNo << ": " << line;
    }
    ++checked;
  }
  EXPECT_GE(checked, 12);
}
