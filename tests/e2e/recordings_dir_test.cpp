// `throng serve --recordings DIR` (apps/throng/recordings_dir.cpp, recording_routes.cpp): the
// listing's figures, path safety (no `..`, no absolute path, no link out of DIR, no hidden file),
// uploads stored under a sanitised unique name only when they are throng recordings, with one
// message naming what was wrong and nothing left behind otherwise; the query-string decoding.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <string>

#include "cli_runner.hpp"
#include "recording_routes.hpp"
#include "recordings_dir.hpp"

namespace throng::cli {
namespace {

namespace fs = std::filesystem;
using e2e::ScratchDir;

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Every file name in `dir`, hidden ones included.
std::vector<std::string> namesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// A real recording of the bottleneck (8 s), made once for the whole suite.
class RecordingsDirTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new ScratchDir("recordings_src");
    const auto run = e2e::runThrong({"run", std::string(THRONG_SOURCE_DIR) + "/scenarios/bottleneck.json", "--duration",
                                     "8", "--out", (scratch_->path() / "bottleneck.sqlite").string(), "--quiet"},
                                    scratch_->path());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    bytes_ = new std::string(readAll(scratch_->path() / "bottleneck.sqlite"));
  }
  static void TearDownTestSuite() {
    delete bytes_;
    delete scratch_;
  }
  void SetUp() override { ASSERT_FALSE(bytes_->empty()); }

  static ScratchDir* scratch_;
  static std::string* bytes_;
  ScratchDir dir_{"recordings_dir"};
};
ScratchDir* RecordingsDirTest::scratch_ = nullptr;
std::string* RecordingsDirTest::bytes_ = nullptr;

TEST_F(RecordingsDirTest, ListsEachRecordingWithItsFiguresAndSkipsOtherFiles) {
  fs::copy_file(scratch_->path() / "bottleneck.sqlite", dir_ / "b.sqlite");
  dir_.write("notes.txt", "not a recording");
  dir_.write(".hidden.sqlite", "hidden");
  dir_.write("broken.sqlite", "SQLite format 3 but not really");
  auto dir = RecordingsDir::open(dir_.path());
  ASSERT_TRUE(dir.ok());
  const auto list = dir->list();
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].name, "b.sqlite");
  EXPECT_EQ(list[0].scenario, "bottleneck");
  EXPECT_NEAR(list[0].duration, 8.0, 0.2);
  EXPECT_GT(list[0].agents, 10u);
  EXPECT_EQ(list[0].size, bytes_->size());
  EXPECT_TRUE(list[0].error.empty());
  EXPECT_EQ(list[1].name, "broken.sqlite");
  EXPECT_FALSE(list[1].error.empty());
  EXPECT_EQ(list[1].agents, 0u);
}

TEST_F(RecordingsDirTest, OpenRefusesAMissingDirectoryOrAFile) {
  EXPECT_FALSE(RecordingsDir::open(dir_ / "nope").ok());
  EXPECT_FALSE(RecordingsDir::open(dir_.write("file", "x")).ok());
}

TEST_F(RecordingsDirTest, ResolveReadsNothingOutsideTheDirectory) {
  ScratchDir outside("recordings_outside");
  fs::copy_file(scratch_->path() / "bottleneck.sqlite", outside / "secret.sqlite");
  fs::create_directory(dir_ / "sub");
  fs::copy_file(scratch_->path() / "bottleneck.sqlite", dir_ / "sub" / "in_sub.sqlite");
  fs::copy_file(scratch_->path() / "bottleneck.sqlite", dir_ / "ok.sqlite");
  fs::create_symlink(outside / "secret.sqlite", dir_ / "out.sqlite");
  fs::create_symlink(dir_ / "ok.sqlite", dir_ / "alias.sqlite");
  fs::create_directory_symlink(outside.path(), dir_ / "outdir.sqlite");
  auto dir = RecordingsDir::open(dir_.path());
  ASSERT_TRUE(dir.ok());

  ASSERT_TRUE(dir->resolve("ok.sqlite").ok());
  EXPECT_EQ(dir->resolve("ok.sqlite").value(), fs::canonical(dir_ / "ok.sqlite"));
  EXPECT_TRUE(dir->resolve("alias.sqlite").ok()) << "a link to a file inside DIR is fine";
  for (const std::string& bad : std::vector<std::string>{"../secret.sqlite", "..", ".", "", "sub/in_sub.sqlite", "sub\\in_sub.sqlite",
                                (outside / "secret.sqlite").string(), "out.sqlite", "outdir.sqlite", "sub",
                                ".hidden.sqlite", "ok.sqlite.txt", "missing.sqlite", std::string("ok\0.sqlite", 10)}) {
    auto r = dir->resolve(bad);
    EXPECT_FALSE(r.ok()) << "resolved '" << bad << "'";
    if (!r.ok()) EXPECT_FALSE(r.errors().front().what.empty());
  }
  // The listing offers only what resolve accepts.
  std::vector<std::string> listed;
  for (const auto& e : dir->list()) listed.push_back(e.name);
  EXPECT_EQ(listed, (std::vector<std::string>{"alias.sqlite", "ok.sqlite"}));
}

TEST_F(RecordingsDirTest, SanitisesNames) {
  EXPECT_EQ(sanitiseRecordingName("museum.sqlite"), "museum.sqlite");
  EXPECT_EQ(sanitiseRecordingName("../../etc/pass wd"), "pass_wd.sqlite");
  EXPECT_EQ(sanitiseRecordingName("C:\\runs\\a;b.sqlite"), "a_b.sqlite");
  EXPECT_EQ(sanitiseRecordingName("...hidden.sqlite"), "hidden.sqlite");
  EXPECT_EQ(sanitiseRecordingName(".."), "recording.sqlite");
  EXPECT_EQ(sanitiseRecordingName(""), "recording.sqlite");
  EXPECT_EQ(sanitiseRecordingName("caf\xc3\xa9.sqlite"), "caf__.sqlite");
  EXPECT_EQ(sanitiseRecordingName(std::string(300, 'a')).size(), 80u + 7u);
}

TEST_F(RecordingsDirTest, StoresAValidUploadUnderAUniqueNameAndNeverOverwrites) {
  fs::copy_file(scratch_->path() / "bottleneck.sqlite", dir_ / "run.sqlite");
  dir_.write("run-2.sqlite", "taken");
  auto dir = RecordingsDir::open(dir_.path());
  ASSERT_TRUE(dir.ok());
  auto stored = dir->store("../run.sqlite", *bytes_, bytes_->size());
  ASSERT_TRUE(stored.ok()) << stored.errors().front().format();
  EXPECT_EQ(stored->name, "run-3.sqlite");
  EXPECT_EQ(stored->scenario, "bottleneck");
  EXPECT_EQ(readAll(dir_ / "run-3.sqlite"), *bytes_);
  EXPECT_EQ(readAll(dir_ / "run-2.sqlite"), "taken");
  EXPECT_EQ(namesIn(dir_.path()), (std::vector<std::string>{"run-2.sqlite", "run-3.sqlite", "run.sqlite"}));
}

TEST_F(RecordingsDirTest, RefusesBadUploadsWithOneMessageAndLeavesNothing) {
  auto dir = RecordingsDir::open(dir_.path());
  ASSERT_TRUE(dir.ok());
  const std::string truncated = bytes_->substr(0, bytes_->size() / 3);
  // An SQLite file that is not a recording: the bundled recording's header and a corrupt rest.
  std::string notThrong = bytes_->substr(0, 100) + std::string(4096, '\0');
  struct Case {
    std::string bytes;
    std::size_t limit;
    std::string says;
  };
  const std::vector<Case> cases{
      {"", 1u << 20, "empty"},
      {*bytes_, 1000, "too large"},
      {R"({"name": "a scenario"})", 1u << 20, "not a SQLite file"},
      {truncated, 1u << 20, "SQLite"},
      {notThrong, 1u << 20, "SQLite"},
  };
  for (const Case& c : cases) {
    auto r = dir->store("upload.sqlite", c.bytes, c.limit);
    ASSERT_FALSE(r.ok()) << c.says;
    ASSERT_EQ(r.errors().size(), 1u);
    const std::string text = r.errors().front().format();
    EXPECT_NE(text.find("upload.sqlite"), std::string::npos) << text;
    EXPECT_NE(text.find(c.says), std::string::npos) << text;
    EXPECT_TRUE(namesIn(dir_.path()).empty()) << "left behind after: " << text;
  }
}

TEST_F(RecordingsDirTest, RefusesASqliteFileThatIsNoThrongRecording) {
  ScratchDir source("recordings_foreign");
  const fs::path foreign = source / "foreign.sqlite";
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(foreign.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "CREATE TABLE shops(name TEXT); INSERT INTO shops VALUES ('bakery');", nullptr, nullptr,
                         nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  // A real recording whose stored scenario no longer loads (same length, so the file stays valid).
  std::string broken = *bytes_;
  std::size_t replaced = 0;
  for (std::size_t at = broken.find("\"populations\""); at != std::string::npos; at = broken.find("\"populations\"", at)) {
    broken.replace(at, 13, "\"populationz\"");
    ++replaced;
  }
  ASSERT_GT(replaced, 0u);

  auto dir = RecordingsDir::open(dir_.path());
  ASSERT_TRUE(dir.ok());
  auto notOurs = dir->store("foreign.sqlite", readAll(foreign), 1u << 20);
  ASSERT_FALSE(notOurs.ok());
  EXPECT_NE(notOurs.errors().front().format().find("trajectory_data"), std::string::npos)
      << notOurs.errors().front().format();
  auto r = dir->store("broken.sqlite", broken, broken.size());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.errors().front().format().find("scenario it stores does not load"), std::string::npos)
      << r.errors().front().format();
  EXPECT_TRUE(namesIn(dir_.path()).empty());
}


}  // namespace
}  // namespace throng::cli
