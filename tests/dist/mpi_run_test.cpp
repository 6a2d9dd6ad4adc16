// End-to-end: `mpirun -np 2 throng run S` (the steer phase shared by two processes, libs/dist)
// writes the same recording as `throng run S`: every table of the two SQLite files, row by row,
// and the same final World::stateHash. Runs mpirun as docs/scaling.md says to (as root too, with
// shared-memory transport only, ranks not pinned so --threads can use both cores).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Ran {
  int status = -1;
  std::string output;  // stdout and stderr
};

Ran shell(const std::string& command) {
  Ran r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) r.output += buffer.data();
  r.status = pclose(pipe);
  return r;
}

class Scratch {
 public:
  explicit Scratch(const std::string& tag) {
    path_ = fs::temp_directory_path() / ("throng-mpi-" + tag + "-" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~Scratch() { fs::remove_all(path_); }
  [[nodiscard]] std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

/// Every row of every table, as text, in rowid order.
std::vector<std::pair<std::string, std::vector<std::string>>> dump(const std::string& file) {
  std::vector<std::pair<std::string, std::vector<std::string>>> tables;
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    ADD_FAILURE() << "cannot open " << file;
    sqlite3_close(db);
    return tables;
  }
  auto rows = [&](const std::string& sql) {
    std::vector<std::string> out;
    sqlite3_stmt* st = nullptr;
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr) != SQLITE_OK) {
      ADD_FAILURE() << sql << ": " << sqlite3_errmsg(db);
      return out;
    }
    while (sqlite3_step(st) == SQLITE_ROW) {
      std::string row;
      for (int c = 0; c < sqlite3_column_count(st); ++c) {
        const auto* blob = static_cast<const char*>(sqlite3_column_blob(st, c));
        row += std::string(blob != nullptr ? blob : "", static_cast<std::size_t>(sqlite3_column_bytes(st, c)));
        row += '\x1f';
      }
      out.push_back(std::move(row));
    }
    sqlite3_finalize(st);
    return out;
  };
  for (const std::string& entry : rows("SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name")) {
    const std::string name = entry.substr(0, entry.size() - 1);
    tables.emplace_back(name, rows("SELECT * FROM \"" + name + "\""));
  }
  sqlite3_close(db);
  return tables;
}

std::string hashOf(const std::string& output) {
  // The JSON summary is the last line that starts with '{'.
  const auto line = output.rfind("\n{");
  const std::size_t start = line == std::string::npos ? 0 : line + 1;
  try {
    const std::string text = output.substr(start, output.find('\n', start) - start);
    return nlohmann::json::parse(text).at("state_hash").get<std::string>();
  } catch (const std::exception&) {
    return "";
  }
}

void expectSameRecording(const std::string& scenario, double duration, int threads) {
  Scratch dir(scenario);
  const std::string exe = THRONG_EXE;
  const std::string file = std::string(THRONG_SOURCE_DIR) + "/scenarios/" + scenario + ".json";
  const std::string args = " run " + file + " --duration " + std::to_string(duration) + " --threads " +
                           std::to_string(threads) + " --json -q --out ";
  const Ran plain = shell(exe + args + (dir / "one.sqlite"));
  ASSERT_EQ(plain.status, 0) << plain.output;
  // --allow-run-as-root: containers run as root; --oversubscribe: fewer cores than ranks is fine;
  // btl self,vader: shared memory only, no network probing; single copy off: no ptrace (CMA) needed.
  const std::string mpirun = std::string(THRONG_MPIEXEC) +
                             " --allow-run-as-root --oversubscribe --bind-to none --mca btl self,vader"
                             " --mca btl_vader_single_copy_mechanism none -np 2 ";
  const Ran split = shell(mpirun + exe + args + (dir / "two.sqlite"));
  ASSERT_EQ(split.status, 0) << split.output;
  EXPECT_NE(split.output.find("\"mpi\":{"), std::string::npos) << "not run on 2 ranks: " << split.output;
  EXPECT_NE(split.output.find("\"ranks\":2"), std::string::npos) << split.output;
  const std::string h1 = hashOf(plain.output), h2 = hashOf(split.output);
  EXPECT_FALSE(h1.empty()) << plain.output;
  EXPECT_EQ(h1, h2) << "final World state differs";

  const auto one = dump(dir / "one.sqlite");
  const auto two = dump(dir / "two.sqlite");
  ASSERT_EQ(one.size(), two.size());
  bool sawTrajectories = false;
  for (std::size_t t = 0; t < one.size(); ++t) {
    ASSERT_EQ(one[t].first, two[t].first);
    const auto& a = one[t].second;
    const auto& b = two[t].second;
    ASSERT_EQ(a.size(), b.size()) << "table " << one[t].first;
    for (std::size_t r = 0; r < a.size(); ++r) ASSERT_EQ(a[r], b[r]) << "table " << one[t].first << ", row " << r;
    if (one[t].first == "trajectory_data") sawTrajectories = !a.empty();
  }
  EXPECT_TRUE(sawTrajectories);
}

}  // namespace

TEST(MpiRun, BottleneckTwoRanksSameRecording) { expectSameRecording("bottleneck", 20.0, 1); }

TEST(MpiRun, MuseumGroupsTwoRanksTwoThreadsSameRecording) { expectSameRecording("museum", 20.0, 2); }

TEST(MpiRun, MallCommonGroundTwoRanksSameRecording) { expectSameRecording("mall", 8.0, 1); }
