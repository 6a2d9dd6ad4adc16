// The network libraries' layering (GUIDE §2), read from their #include lines: libs/net (the
// Boost.Asio names) includes no throng header; the server transport (libs/transport) and the client
// sockets (libs/client) include only core, protocol, net and their own headers, so neither links
// the other; no simulation library includes a network library or Boost.Asio.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

namespace fs = std::filesystem;

namespace {

/// The `#include "throng/<name>/..."` and `<boost/asio...>` lines of libs/<lib> ("file:line: text")
/// that `refused(name)` refuses (Boost.Asio and Beast count as the name "boost").
template <class Refused>
std::vector<std::string> foreignIncludes(const std::string& lib, Refused refused, int& files) {
  const std::regex throngInclude(R"(#\s*include\s*[<"]throng/([a-z_]+)/)");
  const std::regex asioInclude(R"(#\s*include\s*[<"]boost/(asio|beast))");
  std::vector<std::string> found;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(THRONG_SOURCE_DIR) / "libs" / lib)) {
    const auto ext = entry.path().extension();
    if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".hpp")) continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
      std::smatch m;
      const bool foreignThrong = std::regex_search(line, m, throngInclude) && refused(m[1].str());
      const bool foreignAsio = std::regex_search(line, asioInclude) && refused("boost");
      if (foreignThrong || foreignAsio) found.push_back(entry.path().string() + ":" + std::to_string(lineNo) + ": " + line);
    }
  }
  return found;
}

void expectOnly(const std::string& lib, const std::set<std::string>& allowed, int minFiles) {
  int files = 0;
  const auto refused = [&](const std::string& name) { return !allowed.contains(name); };
  for (const auto& hit : foreignIncludes(lib, refused, files)) ADD_FAILURE() << lib << " may not include: " << hit;
  EXPECT_GE(files, minFiles) << "libs/" << lib;
}

TEST(NetLayering, TheAsioNamesIncludeNoThrongHeader) { expectOnly("net", {"boost"}, 1); }

TEST(NetLayering, TheTransportDoesNotIncludeTheClients) {
  expectOnly("transport", {"core", "protocol", "net", "transport", "boost"}, 10);
}

TEST(NetLayering, TheClientsDoNotIncludeTheTransport) {
  expectOnly("client", {"core", "protocol", "net", "client", "boost"}, 8);
}

TEST(NetLayering, NoSimulationLibraryIncludesTheNetwork) {
  const std::set<std::string> network{"net", "transport", "client", "protocol", "hub", "link", "boost"};
  const auto refused = [&](const std::string& name) { return network.contains(name); };
  for (const char* lib : {"core", "nav", "crowd", "common_ground", "sim"}) {
    int files = 0;
    for (const auto& hit : foreignIncludes(lib, refused, files)) {
      ADD_FAILURE() << lib << " may not include: " << hit;
    }
    EXPECT_GT(files, 0) << "libs/" << lib;
  }
}

}  // namespace
