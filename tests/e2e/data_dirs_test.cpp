// Where the program finds its bundled data (apps/throng/data_dirs.hpp): an installed tree's
// <prefix>/share/throng, seen from <prefix>/bin/throng, before the build tree's fallback.
#include "data_dirs.hpp"

#include <filesystem>

#include <gtest/gtest.h>

#include "temp_dir.hpp"

using throng::test::TempDir;

namespace throng::cli {
namespace {

namespace fs = std::filesystem;

TEST(DataDirs, InstalledShareDirIsFoundFromTheExecutable) {
  TempDir prefix("throng-data-dirs");
  const fs::path exe = fs::path(prefix.file("bin")) / "throng";
  EXPECT_TRUE(installedDataDir(exe).empty()) << "no share/throng yet";
  fs::create_directories(prefix.file("share/throng"));
  EXPECT_EQ(installedDataDir(exe), fs::path(prefix.file("share/throng")));
  EXPECT_TRUE(installedDataDir({}).empty());
}

TEST(DataDirs, InstalledSubdirectoryComesBeforeTheBuildTreeFallback) {
  TempDir prefix("throng-data-dirs");
  const fs::path exe = fs::path(prefix.file("bin")) / "throng";
  const fs::path fallback = "/source/web/dist";
  fs::create_directories(prefix.file("share/throng/scenarios"));
  EXPECT_EQ(bundledDataDir(exe, "web", fallback), fallback) << "share/throng/web absent";
  fs::create_directories(prefix.file("share/throng/web"));
  EXPECT_EQ(bundledDataDir(exe, "web", fallback), fs::path(prefix.file("share/throng/web")));
  EXPECT_EQ(bundledDataDir(exe, "scenarios", {}), fs::path(prefix.file("share/throng/scenarios")));
  EXPECT_EQ(bundledDataDir({}, "web", fallback), fallback);
}

}  // namespace
}  // namespace throng::cli
