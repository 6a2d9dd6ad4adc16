// Tests for libs/transport/src/static_files.cpp: percent-decoding, query values, traversal refusal, index.html,
// symbolic links out of the root, Content-Types.
#include "static_files.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <random>

namespace throng::transport::detail {
namespace {
namespace fs = std::filesystem;

TEST(StaticFiles, PercentDecode) {
  EXPECT_EQ(percentDecode("/a%20b"), "/a b");
  EXPECT_EQ(percentDecode("%2e%2E"), "..");
  EXPECT_FALSE(percentDecode("%"));
  EXPECT_FALSE(percentDecode("%4"));
  EXPECT_FALSE(percentDecode("%zz"));
  EXPECT_FALSE(percentDecode("a%00b"));
}

TEST(StaticFiles, QueryValuesAreDecoded) {
  EXPECT_EQ(queryValue("/api/recordings?name=a%20b.sqlite", "name"), "a b.sqlite");
  EXPECT_EQ(queryValue("/api/recordings?x=1&name=..%2Fx.sqlite", "name"), "../x.sqlite");
  EXPECT_EQ(queryValue("/api/recordings?name=a+b", "name"), "a b");
  EXPECT_EQ(queryValue("/api/recordings?name=%2", "name"), std::nullopt);
  EXPECT_EQ(queryValue("/api/recordings?name=%zz", "name"), std::nullopt);
  EXPECT_EQ(queryValue("/api/recordings", "name"), std::nullopt);
  EXPECT_EQ(queryValue("/api/recordings?other=1", "name"), std::nullopt);
  EXPECT_EQ(targetPath("/api/recordings?name=x#y"), "/api/recordings");
}

TEST(StaticFiles, SafeRelativePath) {
  EXPECT_EQ(safeRelativePath("/"), fs::path());
  EXPECT_EQ(safeRelativePath("/a/b.js?x=1#y"), fs::path("a/b.js"));
  EXPECT_EQ(safeRelativePath("//a/./b"), fs::path("a/b"));
  EXPECT_EQ(safeRelativePath("/a..b"), fs::path("a..b"));
  EXPECT_FALSE(safeRelativePath("/../etc/passwd"));
  EXPECT_FALSE(safeRelativePath("/a/../../x"));
  EXPECT_FALSE(safeRelativePath("/%2e%2e/x"));
  EXPECT_FALSE(safeRelativePath("/a/%2E%2E%2fx"));
  EXPECT_FALSE(safeRelativePath("/a\\..\\x"));
  EXPECT_FALSE(safeRelativePath("a/b"));
  EXPECT_FALSE(safeRelativePath(""));
  EXPECT_FALSE(safeRelativePath("*"));
  EXPECT_FALSE(safeRelativePath("http://host/x"));
}

TEST(StaticFiles, ResolveIndexAndLinks) {
  const fs::path base = fs::temp_directory_path() / ("throng_static_" + std::to_string(std::random_device{}()));
  fs::create_directories(base / "www" / "sub");
  std::ofstream(base / "www" / "index.html") << "<p>hi</p>";
  std::ofstream(base / "www" / "sub" / "index.html") << "sub";
  std::ofstream(base / "secret.txt") << "secret";
  fs::create_symlink(base / "secret.txt", base / "www" / "leak.txt");

  const fs::path root = base / "www";
  EXPECT_EQ(resolveStaticFile(root, "/").lookup, StaticLookup::Found);
  EXPECT_EQ(resolveStaticFile(root, "/").path.filename(), "index.html");
  EXPECT_EQ(resolveStaticFile(root, "/sub").path, fs::canonical(root / "sub" / "index.html"));
  EXPECT_EQ(resolveStaticFile(root, "/missing.js").lookup, StaticLookup::NotFound);
  EXPECT_EQ(resolveStaticFile(root, "/../secret.txt").lookup, StaticLookup::BadTarget);
  EXPECT_EQ(resolveStaticFile(root, "/leak.txt").lookup, StaticLookup::NotFound);
  EXPECT_EQ(resolveStaticFile(fs::path(), "/index.html").lookup, StaticLookup::NotFound);
  fs::remove_all(base);
}

TEST(StaticFiles, ContentTypes) {
  EXPECT_EQ(contentTypeFor("a.html"), "text/html; charset=utf-8");
  EXPECT_EQ(contentTypeFor("a.JS"), "text/javascript; charset=utf-8");
  EXPECT_EQ(contentTypeFor("a.css"), "text/css; charset=utf-8");
  EXPECT_EQ(contentTypeFor("a.json"), "application/json");
  EXPECT_EQ(contentTypeFor("a.png"), "image/png");
  EXPECT_EQ(contentTypeFor("a.svg"), "image/svg+xml");
  EXPECT_EQ(contentTypeFor("a.wasm"), "application/wasm");
  EXPECT_EQ(contentTypeFor("a.glb"), "model/gltf-binary");
  EXPECT_EQ(contentTypeFor("a.bin"), "application/octet-stream");
  EXPECT_EQ(contentTypeFor("noext"), "application/octet-stream");
}

}  // namespace
}  // namespace throng::transport::detail
