// `throng edit FILE` as the browser editor uses it: the real binary on a free port, its JSON API
// over HTTP — GET /api/scenario (an empty scenario before FILE exists, then FILE's text), POST
// /api/check (the diagnostics of `throng check`, with pointers), /api/preview (frames in which
// agents move; bad limits refused), /api/save (refused while invalid unless forced, formatted,
// runs), /api/import (a WKT plan → walkable, obstacles, walls; a bad one located), bad JSON and
// Ctrl-C. (The body limit, 413, is tested in tests/transport/http_post_test.cpp.)
#include <gtest/gtest.h>

#include <csignal>
#include <chrono>
#include <regex>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "throng/client/http_client.hpp"

namespace throng::e2e {
namespace {
using namespace std::chrono_literals;
using json = nlohmann::ordered_json;

const char* kRoom = R"({"format": "throng/1", "name": "room", "duration": 30,
  "walkable": [[[0,0],[10,0],[10,6],[0,6]]],
  "obstacles": [[[5,0],[5.2,0],[5.2,2.5],[5,2.5]], [[5,3.5],[5.2,3.5],[5.2,6],[5,6]]],
  "points": [{"id": "exit", "kind": "exit", "polygon": [[9,2],[10,2],[10,4],[9,4]]}],
  "populations": [{"id": "crowd", "groups": 10, "spawn": {"polygon": [[0.5,0.5],[4,0.5],[4,5.5],[0.5,5.5]]},
                   "goals": ["exit"]}]})";

class Editor {
 public:
  explicit Editor(const std::string& file) : dir_("edit") {
    path = dir_ / file;
    process_ = std::make_unique<CliProcess>(std::vector<std::string>{"edit", path.string(), "--port", "0"}, dir_.path());
    const std::regex url(R"(http://127\.0\.0\.1:(\d+)/)");
    for (int i = 0; i < 300 && port == 0; ++i) {
      std::this_thread::sleep_for(20ms);
      std::smatch m;
      const std::string out = process_->outSoFar();
      if (std::regex_search(out, m, url)) port = static_cast<std::uint16_t>(std::stoi(m[1]));
    }
  }
  client::HttpReply get(const std::string& target) const {
    auto reply = client::httpRequest("127.0.0.1", port, "GET", target);
    EXPECT_TRUE(reply.ok());
    return reply.ok() ? reply.value() : client::HttpReply{};
  }
  client::HttpReply post(const std::string& target, const std::string& body) const {
    auto reply = client::httpRequest("127.0.0.1", port, "POST", target, client::HttpBody{body}, 60s);
    EXPECT_TRUE(reply.ok()) << (reply.ok() ? "" : reply.errors().front().format());
    return reply.ok() ? reply.value() : client::HttpReply{};
  }
  CliResult stop() {
    process_->signal(SIGINT);
    return process_->wait(10s);
  }
  std::filesystem::path path;
  std::uint16_t port = 0;

 private:
  ScratchDir dir_;
  std::unique_ptr<CliProcess> process_;
};

TEST(Edit, NewFileStartsFromAnEmptyScenarioAndIsCheckedLikeThrongCheck) {
  Editor editor("new.json");
  ASSERT_NE(editor.port, 0);
  const json start = json::parse(editor.get("/api/scenario").body);
  EXPECT_EQ(start["exists"], false);
  EXPECT_EQ(start["canSave"], true);
  EXPECT_EQ(start["file"], "new.json");
  const json empty = json::parse(start["text"].get<std::string>());
  EXPECT_EQ(empty["format"], "throng/1");

  const json bad = json::parse(editor.post("/api/check", start["text"].get<std::string>()).body);
  EXPECT_EQ(bad["ok"], false);
  ASSERT_FALSE(bad["diagnostics"].empty());
  EXPECT_EQ(bad["diagnostics"][0]["pointer"], "/walkable");
  EXPECT_EQ(bad["diagnostics"][0]["severity"], "error");
  EXPECT_NE(bad["diagnostics"][0]["message"].get<std::string>().find("walkable"), std::string::npos);

  // An exit inside an obstacle cannot be reached: the navmesh check of `throng check`.
  json closed = json::parse(kRoom);
  closed["points"][0]["polygon"] = json::parse("[[5.02,0.5],[5.18,0.5],[5.18,1.5],[5.02,1.5]]");
  const json unreachable = json::parse(editor.post("/api/check", closed.dump()).body);
  EXPECT_EQ(unreachable["ok"], false);
  bool namesGoal = false;
  for (const auto& d : unreachable["diagnostics"]) namesGoal |= d["pointer"].get<std::string>().rfind("/populations/0", 0) == 0 || d["pointer"].get<std::string>().rfind("/points/0", 0) == 0;
  EXPECT_TRUE(namesGoal) << unreachable.dump();

  const json good = json::parse(editor.post("/api/check", kRoom).body);
  EXPECT_EQ(good["ok"], true) << good.dump();
  EXPECT_EQ(good["summary"]["agents_min"], 10);
  EXPECT_EQ(editor.post("/api/check", "{not json").status, 400u);
  EXPECT_EQ(editor.post("/api/nothing", "{}").status, 404u);
  EXPECT_EQ(editor.stop().exitCode, 130);
}

TEST(Edit, PreviewSendsFramesInWhichAgentsMove) {
  Editor editor("room.json");
  ASSERT_NE(editor.port, 0);
  const json request = {{"scenario", json::parse(kRoom)}, {"seconds", 6}, {"fps", 5}};
  const client::HttpReply reply = editor.post("/api/preview", request.dump());
  ASSERT_EQ(reply.status, 200u) << reply.body;
  const json preview = json::parse(reply.body);
  EXPECT_EQ(preview["ok"], true);
  EXPECT_DOUBLE_EQ(preview["fps"].get<double>(), 5.0);
  const json& frames = preview["frames"];
  ASSERT_EQ(frames.size(), 31u);  // t = 0 and 30 more at 5 per second
  EXPECT_NEAR(frames.back()["t"].get<double>(), 6.0, 1e-6);
  const json& first = frames.front();
  ASSERT_EQ(first["ids"].size(), 10u);
  ASSERT_EQ(first["xy"].size(), 20u);
  // Agent 0 walks towards the exit (east).
  const json& last = frames.back();
  ASSERT_FALSE(last["ids"].empty());
  EXPECT_EQ(last["ids"][0], 0);
  EXPECT_GT(last["xy"][0].get<double>(), first["xy"][0].get<double>() + 2.0);

  EXPECT_EQ(editor.post("/api/preview", json{{"scenario", json::parse(kRoom)}, {"seconds", 500}}.dump()).status, 400u);
  EXPECT_EQ(editor.post("/api/preview", json{{"scenario", json::parse(kRoom)}, {"fps", 0}}.dump()).status, 400u);
  EXPECT_EQ(editor.post("/api/preview", json{{"seconds", 5}}.dump()).status, 400u);
  const client::HttpReply invalid = editor.post("/api/preview", json{{"scenario", {{"format", "throng/1"}}}}.dump());
  EXPECT_EQ(invalid.status, 422u);
  EXPECT_FALSE(json::parse(invalid.body)["diagnostics"].empty());
}

TEST(Edit, SaveRefusesAnInvalidScenarioUnlessForcedAndWritesOnlyItsFile) {
  Editor editor("saved.json");
  ASSERT_NE(editor.port, 0);
  const client::HttpReply refused = editor.post("/api/save", json{{"scenario", {{"format", "throng/1"}}}}.dump());
  EXPECT_EQ(refused.status, 422u);
  EXPECT_EQ(json::parse(refused.body)["saved"], false);
  EXPECT_FALSE(std::filesystem::exists(editor.path));

  const client::HttpReply forced =
      editor.post("/api/save", json{{"scenario", {{"format", "throng/1"}}}, {"force", true}}.dump());
  EXPECT_EQ(forced.status, 200u);
  EXPECT_EQ(json::parse(forced.body)["saved"], true);
  EXPECT_EQ(json::parse(forced.body)["ok"], false);
  EXPECT_EQ(readFile(editor.path), "{\n  \"format\": \"throng/1\"\n}\n");

  const client::HttpReply saved = editor.post("/api/save", json{{"scenario", json::parse(kRoom)}}.dump());
  EXPECT_EQ(saved.status, 200u) << saved.body;
  const std::string text = readFile(editor.path);
  // Formatted for diffs as `throng import` writes (io::formatJsonForDiffs): a point per line.
  EXPECT_NE(text.find("\n  \"walkable\": [\n    [\n      [0, 0],\n      [10, 0],\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n  \"name\": \"room\",\n"), std::string::npos) << text;  // key order kept
  EXPECT_EQ(json::parse(text), json::parse(kRoom));
  const json reread = json::parse(editor.get("/api/scenario").body);
  EXPECT_EQ(reread["exists"], true);
  EXPECT_EQ(reread["text"], text);
  // Only FILE is written: no temp file is left beside it.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(editor.path.parent_path())) ++files;
  EXPECT_EQ(files, 1u);
  editor.stop();

  const CliResult check = runThrong({"check", editor.path.string()}, editor.path.parent_path());
  EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
  const CliResult run = runThrong({"run", editor.path.string(), "--duration", "5", "--quiet"}, editor.path.parent_path());
  EXPECT_EQ(run.exitCode, 0) << run.out << run.err;
}

TEST(Edit, ImportsAFloorPlanAsAFragment) {
  Editor editor("plan.json");
  ASSERT_NE(editor.port, 0);
  const json request = {{"name", "ground.wkt"},
                        {"text", "GEOMETRYCOLLECTION (POLYGON ((0 0, 10 0, 10 6, 0 6)), LINESTRING (5 0, 5 2.5))"}};
  const client::HttpReply reply = editor.post("/api/import", request.dump());
  ASSERT_EQ(reply.status, 200u) << reply.body;
  const json plan = json::parse(reply.body);
  EXPECT_EQ(plan["ok"], true);
  ASSERT_EQ(plan["fragment"]["walls"].size(), 1u);
  EXPECT_EQ(plan["fragment"]["walls"][0]["line"], json::parse("[[5, 0], [5, 2.5]]"));
  ASSERT_EQ(plan["fragment"]["walkable"].size(), 1u);

  const client::HttpReply bad = editor.post("/api/import", json{{"name", "ground.wkt"}, {"text", "POLYGON ((0 0, 1 0"}}.dump());
  EXPECT_EQ(bad.status, 422u);
  const json problems = json::parse(bad.body);
  ASSERT_FALSE(problems["diagnostics"].empty());
  EXPECT_GT(problems["diagnostics"][0]["line"].get<int>(), 0);
  EXPECT_EQ(editor.post("/api/import", json{{"name", "ground.pdf"}, {"text", "x"}}.dump()).status, 400u);
  EXPECT_EQ(editor.post("/api/import", json{{"text", "x"}}.dump()).status, 400u);
}

}  // namespace
}  // namespace throng::e2e
