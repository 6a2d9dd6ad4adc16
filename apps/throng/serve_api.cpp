// `throng serve`'s dynamic HTTP answers (serve_api.hpp): the World's groups, crowds and agents as
// JSON (groupsJson, crowdsJson, agentJson), WorldQueries' queue of questions and exit commands,
// and HttpApi's routes.
#include "serve_api.hpp"

#include <algorithm>
#include <chrono>
#include <map>

#include <nlohmann/json.hpp>

#include "output.hpp"
#include "throng/hub/motion_library.hpp"
#include "throng/sim/animation.hpp"

namespace throng::cli::serve {
namespace {

/// The groups as they are now (most spawn after the start, so the world description lacks them).
nlohmann::json groupsJson(const sim::World& world) {
  nlohmann::json groups = nlohmann::json::array();
  // world.desc(): crowds inserted at run time appended their populations (and groups).
  const sim::ScenarioDesc& desc = world.desc();
  for (std::size_t g = 0; g < world.groupCount(); ++g) {
    const auto info = world.groupInfo(world.groupById(static_cast<std::uint32_t>(g)));
    if (!info) continue;
    groups.push_back({{"id", info->id},
                      {"population", info->population < desc.populations.size() ? desc.populations[info->population].id
                                                                                 : std::string()},
                      {"members", info->members}, {"leader", info->leader}, {"guided", info->guided},
                      {"waiting", info->waiting}});
  }
  return groups;
}

/// Crowds inserted at run time (InsertCrowd, timeline), in insertion order, with their owners.
nlohmann::json crowdsJson(const sim::World& world, const std::map<std::string, std::uint32_t>& owners) {
  nlohmann::json crowds = nlohmann::json::array();
  const sim::ScenarioDesc& desc = world.desc();
  for (const sim::CrowdInfo& c : world.crowds()) {
    nlohmann::json populations = nlohmann::json::array();
    for (std::uint32_t p = c.firstPopulation; p < c.firstPopulation + c.populations && p < desc.populations.size(); ++p) {
      populations.push_back(desc.populations[p].id);
    }
    // Its owner: the participant that inserted it (only it may remove it); null: the scenario's.
    const auto owner = owners.find(c.id);
    crowds.push_back({{"id", c.id}, {"index", c.index}, {"applied", c.applied}, {"removed", c.removed},
                      {"insertTick", c.insertTick}, {"populations", populations},
                      {"owner", owner == owners.end() ? nlohmann::json(nullptr) : nlohmann::json(owner->second)}});
  }
  return crowds;
}

/// What the simulation thread did not answer within a second.
transport::HttpResponse simulationTimeout() {
  return jsonResponse(503, R"({"error":"the simulation did not answer in time"})");
}

/// One agent's state, goal, coordination and Common Ground script, for GET /api/agent/<id>.
nlohmann::json agentJson(const sim::AgentInfo& info, const sim::ScenarioDesc& d, const std::vector<sim::ClipInfo>& clips,
                         const std::vector<sim::ScriptRecord>& records) {
  nlohmann::json j = {{"id", info.id}, {"group", info.group},
                      {"population", info.population < d.populations.size() ? d.populations[info.population].id : ""},
                      {"state", info.state}, {"position", {info.position.x, info.position.y}},
                      {"target", {info.target.x, info.target.y}}, {"speed", info.speed},
                      {"guided", info.guided},
                      {"behaviour", info.clip < clips.size() ? clips[info.clip].name : "?"}};
  if (info.goalPoint < d.points.size()) {
    const sim::PointDesc& p = d.points[info.goalPoint];
    j["goal"] = {{"point", p.id}, {"category", p.category}, {"action", p.action}};
  } else {
    j["goal"] = nullptr;
  }
  j["coordination"] = info.coordination == 0xffffffffu ? nlohmann::json(nullptr) : nlohmann::json(info.coordination);
  j["following"] = info.followedAgent == 0xffffffffu ? nlohmann::json(nullptr) : nlohmann::json(info.followedAgent);
  nlohmann::json script = nlohmann::json::array();
  for (const sim::ScriptRecord& r : records) {
    script.push_back({{"coordination", r.coordination}, {"seq", r.seq}, {"role", r.role}, {"step", r.step},
                      {"behaviour", r.behaviour}, {"motion", r.motion}, {"start", r.start}, {"duration", r.duration},
                      {"plannedStart", r.plannedStart}, {"plannedDuration", r.plannedDuration},
                      {"targetAgent", r.targetType == 2 ? nlohmann::json(r.targetAgent) : nlohmann::json(nullptr)}});
  }
  j["script"] = std::move(script);
  return j;
}

/// The Content-Type of a world model's file by its name.
std::string modelContentType(const std::string& name) {
  if (name.ends_with(".glb")) return "model/gltf-binary";
  if (name.ends_with(".gltf")) return "model/gltf+json";
  if (name.ends_with(".png")) return "image/png";
  if (name.ends_with(".jpg") || name.ends_with(".jpeg")) return "image/jpeg";
  return "application/octet-stream";
}

}  // namespace

std::future<std::optional<sim::AgentInfo>> WorldQueries::askAgent(std::uint32_t id) {
  auto query = std::make_shared<AgentQuery>();
  query->id = id;
  auto future = query->answer.get_future();
  std::lock_guard lock(mutex_);
  agents_.push_back(std::move(query));
  return future;
}

std::future<bool> WorldQueries::askSetExitOpen(std::string id, bool open) {
  auto command = std::make_shared<ExitCommand>();
  command->id = std::move(id);
  command->open = open;
  auto future = command->found.get_future();
  std::lock_guard lock(mutex_);
  exits_.push_back(std::move(command));
  return future;
}

void WorldQueries::answer(sim::World* world, const hub::Hub& hub) {
  std::lock_guard lock(mutex_);
  for (const auto& c : exits_) c->found.set_value(world != nullptr && world->setExitOpen(c->id, c->open));
  exits_.clear();
  for (const auto& q : agents_) q->answer.set_value(world ? world->agentInfo(q->id) : std::nullopt);
  agents_.clear();
  if (!groups_.empty()) {
    const std::string text = dumpJson(world ? groupsJson(*world) : nlohmann::json::array());
    for (const auto& q : groups_) q->set_value(text);
    groups_.clear();
  }
  if (!crowds_.empty()) {
    const std::string text = dumpJson(world ? crowdsJson(*world, hub.crowdOwners()) : nlohmann::json::array());
    for (const auto& q : crowds_) q->set_value(text);
    crowds_.clear();
  }
}

std::future<std::string> WorldQueries::ask(TextQueries& queries) {
  auto query = std::make_shared<std::promise<std::string>>();
  auto future = query->get_future();
  std::lock_guard lock(mutex_);
  queries.push_back(std::move(query));
  return future;
}

transport::HttpResponse jsonResponse(unsigned status, std::string body) {
  return transport::HttpResponse{status, "application/json", std::move(body), {}};
}

HttpApi::HttpApi(const Served& served, hub::Hub& hub, const Bridge& bridge, WorldQueries& queries, TickWindow& window,
        const hub::TickWatch& tickWatch)
    : served_(served),
      hub_(hub),
      bridge_(bridge),
      queries_(queries),
      window_(window),
      tickWatch_(tickWatch),
      clipTable_(sim::animationClips(served.live.scenario.desc)) {}

std::optional<transport::HttpResponse> HttpApi::operator()(std::string_view target) const {
  const std::string_view path = target.substr(0, target.find('?'));
  if (path == "/api/groups" || path == "/api/crowds") {
    return waitForText(path == "/api/groups" ? queries_.askGroups() : queries_.askCrowds());
  }
  constexpr std::string_view kAgent = "/api/agent/";
  if (path.starts_with(kAgent)) return agent(path.substr(kAgent.size()));
  if (path == "/api/status") return status();
  if (path == "/api/world") return jsonResponse(200, served_.worldJson);
  constexpr std::string_view kModel = "/api/world/model";
  if (path == kModel || path.starts_with("/api/world/model/")) return model(path.substr(kModel.size()));
  constexpr std::string_view kMotions = "/motions/";
  if (path.starts_with(kMotions) && path.ends_with(".bvh")) {
    return motion(path.substr(kMotions.size(), path.size() - kMotions.size() - 4));
  }
  return std::nullopt;
}

transport::HttpResponse HttpApi::waitForText(std::future<std::string> future) {
  if (future.wait_for(std::chrono::milliseconds(1000)) != std::future_status::ready) return simulationTimeout();
  return jsonResponse(200, future.get());
}

transport::HttpResponse HttpApi::agent(std::string_view digits) const {
  const bool numeric = !digits.empty() && digits.size() <= 9 &&
                       std::all_of(digits.begin(), digits.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
  if (!numeric) return jsonResponse(400, R"({"error":"expected /api/agent/<id>, id a number"})");
  std::uint64_t id = 0;
  for (char ch : digits) id = id * 10 + static_cast<std::uint64_t>(ch - '0');
  auto future = queries_.askAgent(static_cast<std::uint32_t>(id));
  if (future.wait_for(std::chrono::milliseconds(1000)) != std::future_status::ready) return simulationTimeout();
  const std::optional<sim::AgentInfo> info = future.get();
  if (!info) return jsonResponse(404, R"j({"error":"no such agent (not spawned yet, or left)"})j");
  return jsonResponse(200, dumpJson(agentJson(*info, served_.live.scenario.desc, clipTable_, hub_.agentScript(info->id))));
}

transport::HttpResponse HttpApi::status() const {
  const hub::HubStatus s = hub_.status();
  nlohmann::json clients = nlohmann::json::array();
  for (const hub::ClientStatus& c : s.perClient) {
    clients.push_back({{"name", c.name}, {"participant", c.participant}, {"participantId", c.participantId},
                       {"granularity", c.granularity}, {"granularityReason", c.granularityReason}, {"kbitPerSecond", c.kbitPerSecond},
                       {"roundTripMs", c.roundTripMs}, {"framesSent", c.framesSent},
                       {"agentsInView", c.agentsInView}, {"guiding", c.guiding}});
  }
  nlohmann::json j = {{"clients", s.clients}, {"participants", s.participants}, {"crowdFrames", s.crowdFrames},
                      {"crowdBytes", s.crowdBytes}, {"perClient", std::move(clients)}};
  {
    const hub::TickReport r = tickWatch_.report(bridge_.now());
    std::lock_guard lock(window_.mutex);
    j["tick"] = {{"median_ms", window_.tickMedianMs}, {"p99_ms", window_.tickP99Ms}, {"late", r.late}, {"stalls", r.stalls},
                 {"longest_ms", r.longestMs}, {"running_ms", r.runningMs}, {"rate", served_.tickRate},
                 {"publish_median_ms", window_.publishMedianMs}, {"publish_p99_ms", window_.publishP99Ms}};
  }
  return jsonResponse(200, dumpJson(j));
}

std::optional<transport::HttpResponse> HttpApi::post(const transport::HttpRequest& request) const {
  const std::string_view target = request.target;
  const std::string_view path = target.substr(0, target.find('?'));
  constexpr std::string_view kExits = "/api/exits/";
  if (!path.starts_with(kExits)) return std::nullopt;
  return setExitOpen(path.substr(kExits.size()), request.body);
}

transport::HttpResponse HttpApi::setExitOpen(std::string_view encodedId, const std::string& body) const {
  const std::optional<std::string> id = transport::percentDecode(encodedId);
  if (!id || id->empty()) {
    return jsonResponse(400, R"j({"error":"expected /api/exits/<id>, id the exit point's id (percent-encoded)"})j");
  }
  const nlohmann::json request = nlohmann::json::parse(body, nullptr, false);
  if (!request.is_object() || request.size() != 1 || !request.contains("open") || !request["open"].is_boolean()) {
    return jsonResponse(400, R"({"error":"expected the body {\"open\": true} or {\"open\": false}"})");
  }
  if (served_.replay) return jsonResponse(409, R"({"error":"a recording is played: its exits cannot be opened or closed"})");
  const bool open = request["open"].get<bool>();
  auto future = queries_.askSetExitOpen(*id, open);
  if (future.wait_for(std::chrono::milliseconds(1000)) != std::future_status::ready) return simulationTimeout();
  if (!future.get()) {
    return jsonResponse(404, dumpJson({{"error", "no exit \"" + *id + "\"; expected the id of a point of kind \"exit\""}}));
  }
  return jsonResponse(200, dumpJson({{"id", *id}, {"open", open}}));
}

transport::HttpResponse HttpApi::motion(std::string_view id) const {
  const hub::MotionLibrary& motions = served_.live.motions;
  std::size_t index = 0;
  for (char ch : id) {
    if (ch < '0' || ch > '9' || index > 100000) return transport::HttpResponse{404, "text/plain", "no such clip\n", {}};
    index = index * 10 + static_cast<std::size_t>(ch - '0');
  }
  if (id.empty() || index >= motions.clips().size() || motions.clipFile(index).empty()) {
    return transport::HttpResponse{404, "text/plain", "no such clip\n", {}};
  }
  return transport::HttpResponse{200, "text/plain; charset=utf-8", {}, motions.clipFile(index)};
}

/// GET /api/world/model: {"url": where the world's glTF file is, or null when the world is none,
/// with "missing": why, for a recording whose glTF file is not served};
/// /api/world/model/world.gltf (or .glb): the file; /api/world/model/<uri>: a resource it names
/// (WorldModel::resources), from its directory. Answered 200 with a null url rather than 404: the
/// viewer asks every live server, and a browser logs each failed fetch.
transport::HttpResponse HttpApi::model(std::string_view rest) const {
  const WorldModel& m = served_.model;
  if (rest.empty() || rest == "/") {
    if (m.file.empty()) {
      return jsonResponse(200, m.missing.empty() ? R"({"url":null})" : dumpJson({{"url", nullptr}, {"missing", m.missing}}));
    }
    return jsonResponse(200, dumpJson({{"url", "/api/world/model/" + m.servedName()}}));
  }
  const std::string name(rest.substr(1));
  if (m.file.empty()) return jsonResponse(404, R"({"error":"the world served is no glTF file"})");
  if (name == m.servedName()) return transport::HttpResponse{200, modelContentType(name), {}, m.file};
  if (std::find(m.resources.begin(), m.resources.end(), name) != m.resources.end()) {
    return transport::HttpResponse{200, modelContentType(name), {}, m.file.parent_path() / name};
  }
  return jsonResponse(404, R"({"error":"no such file of the world model"})");
}

}  // namespace throng::cli::serve
