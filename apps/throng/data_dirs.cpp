// Where the program finds its bundled data — see data_dirs.hpp.
#include "data_dirs.hpp"

namespace throng::cli {

std::filesystem::path installedDataDir(const std::filesystem::path& exe) {
  if (exe.empty()) return {};
  const auto dir = (exe.parent_path() / ".." / "share" / "throng").lexically_normal();
  std::error_code ec;
  return std::filesystem::is_directory(dir, ec) ? dir : std::filesystem::path{};
}

std::filesystem::path bundledDataDir(const std::filesystem::path& exe, std::string_view sub,
                                     const std::filesystem::path& buildTreeFallback) {
  const auto installed = installedDataDir(exe);
  if (!installed.empty()) {
    std::error_code ec;
    const auto dir = installed / sub;
    if (std::filesystem::is_directory(dir, ec)) return dir;
  }
  return buildTreeFallback;
}

}  // namespace throng::cli
