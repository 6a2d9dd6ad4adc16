// The C API's entry points (include/throng/throng.h): each checks its arguments and handle, calls
// the C++ libraries inside `guarded` (no exception crosses the C boundary; each becomes a status and
// a thread-local message), and copies results into the caller's memory. Scenarios are loaded and
// crowds validated by libs/io as `throng check` does; worlds are Sessions (session.hpp).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <sstream>
#include <string>

#include "handles.hpp"
#include "session.hpp"
#include "throng/core/diagnostic.hpp"
#include "throng/io/crowd_loader.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/recording/recorder.hpp"
#include "throng/throng.h"

namespace {

using throng::capi::Registry;
using throng::capi::Session;
using throng::capi::WorldLease;
namespace core = throng::core;
namespace io = throng::io;
namespace sim = throng::sim;

// The last error of this thread. A plain pointer (trivially destructible) so that calls made after
// the thread's thread_local destructors ran (a static's destructor at exit freeing a handle) still
// find valid storage; ErrorCleanup frees the text when the thread ends.
thread_local char* tlsLastError = nullptr;
struct ErrorCleanup {
  ErrorCleanup() = default;
  ErrorCleanup(const ErrorCleanup&) = delete;
  ErrorCleanup& operator=(const ErrorCleanup&) = delete;
  ~ErrorCleanup() {
    std::free(tlsLastError);
    tlsLastError = nullptr;
  }
};
thread_local ErrorCleanup tlsErrorCleanup;

void clearLastError() {
  if (tlsLastError != nullptr) tlsLastError[0] = '\0';
}

throng_status fail(throng_status status, const std::string& message) {
  (void)&tlsErrorCleanup;  // registers this thread's cleanup
  char* text = static_cast<char*>(std::malloc(message.size() + 1));
  if (text != nullptr) std::memcpy(text, message.c_str(), message.size() + 1);
  std::free(tlsLastError);
  tlsLastError = text;  // NULL when out of memory: throng_last_error() then says ""
  return status;
}

/// Runs `body` with the last error cleared; any exception becomes THRONG_ERROR_INTERNAL.
template <typename Body>
throng_status guarded(Body&& body) noexcept {
  try {
    clearLastError();
    return body();
  } catch (const std::bad_alloc&) {
    return fail(THRONG_ERROR_INTERNAL, "out of memory");
  } catch (const std::exception& e) {
    return fail(THRONG_ERROR_INTERNAL, std::string("internal error: ") + e.what());
  } catch (...) {
    return fail(THRONG_ERROR_INTERNAL, "internal error");
  }
}

/// A copy of `text` the caller frees with throng_string_free (std::free).
char* copyText(const std::string& text) {
  char* out = static_cast<char*>(std::malloc(text.size() + 1));
  if (out == nullptr) throw std::bad_alloc();
  std::memcpy(out, text.c_str(), text.size() + 1);
  return out;
}

/// THRONG_ERROR_INVALID_SCENARIO with every diagnostic, one per line, as `throng check` prints them.
throng_status refuse(const core::Diagnostics& diagnostics, char** outDiagnostics) {
  const std::string text = core::formatAll(diagnostics);
  if (outDiagnostics != nullptr) *outDiagnostics = copyText(text);
  return fail(THRONG_ERROR_INVALID_SCENARIO, text);
}

throng_status nullArgument(const char* function, const char* name) {
  return fail(THRONG_ERROR_NULL_ARGUMENT, std::string(function) + ": " + name + " is NULL");
}

throng_status leaseFailed(const char* function, const WorldLease& lease) {
  switch (lease.status()) {
    case THRONG_ERROR_NULL_ARGUMENT: return nullArgument(function, "world");
    case THRONG_ERROR_BUSY: return fail(THRONG_ERROR_BUSY, std::string(function) + ": another thread is inside a call on this world");
    default: return fail(THRONG_ERROR_BAD_HANDLE, std::string(function) + ": not a live throng_world (never created, or freed)");
  }
}

throng_status notFinite(const char* function, const char* name, double value) {
  return fail(THRONG_ERROR_INVALID_ARGUMENT, std::string(function) + ": " + name + " must be a finite number (within float range for coordinates), got " + std::to_string(value));
}

/// A coordinate the World stores as a float: finite, and finite once rounded to float.
bool fitsFloat(double value) { return std::isfinite(value) && std::fabs(value) <= std::numeric_limits<float>::max(); }

/// A validated scenario as a new handle.
throng_status adopt(core::Result<io::LoadedScenario> loaded, throng_scenario** out, char** outDiagnostics) {
  if (!loaded) return refuse(loaded.errors(), outDiagnostics);
  auto s = std::make_unique<throng_scenario>(throng_scenario{std::make_shared<const io::LoadedScenario>(std::move(loaded).value())});
  Registry::instance().add(s.get());
  *out = s.release();
  return THRONG_OK;
}

throng_status checkOptions(const throng_world_options& o) {
  if (o.threads < 0 || o.threads > 1024) {
    return fail(THRONG_ERROR_INVALID_ARGUMENT, "throng_world_create: threads must be in [0, 1024] (0: every hardware thread), got " + std::to_string(o.threads));
  }
  if (!std::isfinite(o.duration) || o.duration < 0) {
    return fail(THRONG_ERROR_INVALID_ARGUMENT, "throng_world_create: duration must be a finite number >= 0 [s] (0 keeps the scenario's), got " + std::to_string(o.duration));
  }
  return THRONG_OK;
}

/// The file's text, or a diagnostic naming it.
core::Result<std::string> readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  if (!in || in.bad()) {
    core::Diagnostic d;
    d.source = path;
    d.what = "cannot read the file";
    d.expected = "a readable throng-crowd/1 JSON file";
    return d;
  }
  return text.str();
}

throng_status insertCrowd(Session& session, const std::string& text, const std::string& source, uint32_t* outIndex,
                          char** outDiagnostics) {
  auto crowd = io::parseCrowd(text, source, session.world());
  if (!crowd) return refuse(crowd.errors(), outDiagnostics);
  auto index = session.world().insertCrowd(crowd.value());
  if (!index) return refuse(index.errors(), outDiagnostics);
  if (outIndex != nullptr) *outIndex = index.value();
  return THRONG_OK;
}

/// Copies the requested columns of `frame` (count already checked against the capacity).
void copyAgents(const Session& session, const sim::Frame& f, const throng_agent_arrays& a) {
  const std::size_t n = f.size();
  if (a.ids != nullptr) std::copy_n(f.ids.data(), n, a.ids);
  for (std::size_t i = 0; i < n; ++i) {
    if (a.positions != nullptr) a.positions[2 * i] = f.posX[i], a.positions[2 * i + 1] = f.posY[i];
    if (a.velocities != nullptr) a.velocities[2 * i] = f.velX[i], a.velocities[2 * i + 1] = f.velY[i];
    if (a.headings != nullptr) a.headings[2 * i] = f.oriX[i], a.headings[2 * i + 1] = f.oriY[i];
  }
  if (a.heights != nullptr) {
    if (f.posZ.empty()) std::fill_n(a.heights, n, 0.0f);
    else std::copy_n(f.posZ.data(), n, a.heights);
  }
  if (a.modes != nullptr) {
    std::transform(f.mode.begin(), f.mode.end(), a.modes, [](sim::AgentMode m) { return static_cast<uint8_t>(m); });
  }
  if (a.clips != nullptr) std::copy_n(f.clip.data(), n, a.clips);
  if (a.phases != nullptr) std::copy_n(f.phase.data(), n, a.phases);
  if (a.groups != nullptr) {
    const auto groups = session.groupsOf(f);
    std::copy(groups.begin(), groups.end(), a.groups);
  }
}

/// throng_world_guide and _at_height: `height` only on a multi-level world.
throng_status guide(throng_world* world, uint32_t group, double x, double y, std::optional<double> height) {
  const char* function = height ? "throng_world_guide_at_height" : "throng_world_guide";
  const WorldLease lease(world);
  if (lease.status() != THRONG_OK) return leaseFailed(function, lease);
  if (!fitsFloat(x)) return notFinite(function, "x", x);
  if (!fitsFloat(y)) return notFinite(function, "y", y);
  if (height && !fitsFloat(*height)) return notFinite(function, "height", *height);
  sim::World& w = lease.session().world();
  const sim::GroupId g = w.groupById(group);
  const core::Vec2 p{static_cast<float>(x), static_cast<float>(y)};
  if (!(height ? w.guide(g, p, static_cast<float>(*height)) : w.guide(g, p))) {
    return fail(THRONG_ERROR_NOT_FOUND, std::string(function) + ": no group with id " + std::to_string(group));
  }
  return THRONG_OK;
}

throng_status stepEnded(throng::capi::StepEnd end, const char* function) {
  if (end == throng::capi::StepEnd::WriteFailed) {
    return fail(THRONG_ERROR_IO, std::string(function) + ": writing the recording failed; close it with throng_world_record_close for the error");
  }
  return THRONG_OK;
}

}  // namespace

extern "C" {

const char* throng_version(void) { return THRONG_VERSION_STRING; }

uint32_t throng_api_version(void) { return THRONG_API_VERSION; }

const char* throng_status_name(throng_status status) {
  switch (status) {
    case THRONG_OK: return "THRONG_OK";
    case THRONG_ERROR_NULL_ARGUMENT: return "THRONG_ERROR_NULL_ARGUMENT";
    case THRONG_ERROR_BAD_HANDLE: return "THRONG_ERROR_BAD_HANDLE";
    case THRONG_ERROR_INVALID_ARGUMENT: return "THRONG_ERROR_INVALID_ARGUMENT";
    case THRONG_ERROR_INVALID_SCENARIO: return "THRONG_ERROR_INVALID_SCENARIO";
    case THRONG_ERROR_NOT_FOUND: return "THRONG_ERROR_NOT_FOUND";
    case THRONG_ERROR_BUFFER_TOO_SMALL: return "THRONG_ERROR_BUFFER_TOO_SMALL";
    case THRONG_ERROR_WRONG_STATE: return "THRONG_ERROR_WRONG_STATE";
    case THRONG_ERROR_BUSY: return "THRONG_ERROR_BUSY";
    case THRONG_ERROR_IO: return "THRONG_ERROR_IO";
    case THRONG_ERROR_INTERNAL: return "THRONG_ERROR_INTERNAL";
  }
  return "unknown";
}

const char* throng_last_error(void) { return tlsLastError != nullptr ? tlsLastError : ""; }

void throng_string_free(char* text) { std::free(text); }

throng_status throng_scenario_load_file(const char* path, throng_scenario** out_scenario, char** out_diagnostics) {
  return guarded([&] {
    if (out_diagnostics != nullptr) *out_diagnostics = nullptr;
    if (path == nullptr) return nullArgument("throng_scenario_load_file", "path");
    if (out_scenario == nullptr) return nullArgument("throng_scenario_load_file", "out_scenario");
    return adopt(io::loadScenarioFile(path), out_scenario, out_diagnostics);
  });
}

throng_status throng_scenario_load_json(const char* json, const char* source, throng_scenario** out_scenario,
                                        char** out_diagnostics) {
  return guarded([&] {
    if (out_diagnostics != nullptr) *out_diagnostics = nullptr;
    if (json == nullptr) return nullArgument("throng_scenario_load_json", "json");
    if (out_scenario == nullptr) return nullArgument("throng_scenario_load_json", "out_scenario");
    return adopt(io::parseScenario(json, source != nullptr ? source : "<string>"), out_scenario, out_diagnostics);
  });
}

throng_status throng_scenario_free(throng_scenario* scenario) {
  return guarded([&] {
    if (scenario == nullptr) return THRONG_OK;
    if (!Registry::instance().removeScenario(scenario)) {
      return fail(THRONG_ERROR_BAD_HANDLE, "throng_scenario_free: not a live throng_scenario (never loaded, or freed)");
    }
    delete scenario;
    return THRONG_OK;
  });
}

throng_status throng_scenario_info_get(const throng_scenario* scenario, throng_scenario_info* out_info) {
  return guarded([&] {
    if (scenario == nullptr) return nullArgument("throng_scenario_info_get", "scenario");
    if (out_info == nullptr) return nullArgument("throng_scenario_info_get", "out_info");
    const auto loaded = Registry::instance().scenario(scenario);
    if (!loaded) return fail(THRONG_ERROR_BAD_HANDLE, "throng_scenario_info_get: not a live throng_scenario");
    const sim::ScenarioDesc& d = loaded->desc;
    throng_scenario_info info{d.seed, d.duration, d.dt, static_cast<uint32_t>(d.populations.size()),
                              static_cast<uint32_t>(d.points.size()), 0, 0};
    for (const auto& p : d.populations) {
      info.agents_min += static_cast<uint64_t>(p.groups) * p.sizeMin;
      info.agents_max += static_cast<uint64_t>(p.groups) * p.sizeMax;
    }
    *out_info = info;
    return THRONG_OK;
  });
}

throng_world_options throng_world_options_default(void) {
  throng_world_options o;
  o.seed = 0;
  o.use_seed = 0;
  o.threads = 1;
  o.duration = 0.0;
  return o;
}

throng_status throng_world_create(const throng_scenario* scenario, const throng_world_options* options,
                                  throng_world** out_world) {
  return guarded([&] {
    if (scenario == nullptr) return nullArgument("throng_world_create", "scenario");
    if (out_world == nullptr) return nullArgument("throng_world_create", "out_world");
    const throng_world_options o = options != nullptr ? *options : throng_world_options_default();
    if (const throng_status bad = checkOptions(o); bad != THRONG_OK) return bad;
    auto loaded = Registry::instance().scenario(scenario);
    if (!loaded) return fail(THRONG_ERROR_BAD_HANDLE, "throng_world_create: not a live throng_scenario");
    throng::capi::SessionOptions so;
    if (o.use_seed != 0) so.seed = o.seed;
    so.threads = o.threads;
    if (o.duration > 0) so.duration = o.duration;
    auto session = Session::create(std::move(loaded), so);
    if (!session) return refuse(session.errors(), nullptr);
    auto w = std::make_unique<throng_world>(throng_world{std::move(session).value()});
    Registry::instance().add(w.get());
    *out_world = w.release();
    return THRONG_OK;
  });
}

throng_status throng_world_free(throng_world* world) {
  return guarded([&] {
    if (world == nullptr) return THRONG_OK;
    const throng_status removed = Registry::instance().removeWorld(world);
    if (removed == THRONG_ERROR_BUSY) return fail(removed, "throng_world_free: another thread is inside a call on this world");
    if (removed != THRONG_OK) return fail(removed, "throng_world_free: not a live throng_world (never created, or freed)");
    std::unique_ptr<throng_world> owned(world);
    if (!owned->session->recording()) return THRONG_OK;
    std::uint64_t frames = 0;
    const core::Status closed = owned->session->closeRecording(frames);
    if (!closed) return fail(THRONG_ERROR_IO, "throng_world_free: the recording failed: " + core::formatAll(closed.errors()));
    return THRONG_OK;
  });
}

throng_status throng_world_step(throng_world* world, uint64_t ticks, uint64_t* out_stepped) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_step", lease);
    Session& s = lease.session();
    if (s.world().finished() && ticks > 0) {
      return fail(THRONG_ERROR_WRONG_STATE, "throng_world_step: the world is finished: every agent has left");
    }
    std::uint64_t stepped = 0;
    const auto end = s.step(ticks, stepped);
    if (out_stepped != nullptr) *out_stepped = stepped;
    return stepEnded(end, "throng_world_step");
  });
}

throng_status throng_world_run(throng_world* world, double until_s) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_run", lease);
    if (!std::isfinite(until_s)) return notFinite("throng_world_run", "until_s", until_s);
    if (until_s < 0) return fail(THRONG_ERROR_INVALID_ARGUMENT, "throng_world_run: until_s must be >= 0 [s]");
    return stepEnded(lease.session().run(until_s), "throng_world_run");
  });
}

throng_status throng_world_stats_get(throng_world* world, throng_world_stats* out_stats) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_stats_get", lease);
    if (out_stats == nullptr) return nullArgument("throng_world_stats_get", "out_stats");
    const Session& s = lease.session();
    const sim::WorldStats& w = s.world().stats();
    throng_world_stats out{};
    out.tick = w.tick;
    out.time = w.time;
    out.dt = s.desc().dt;
    out.duration = s.desc().duration;
    out.seed = s.desc().seed;
    out.spawned = w.spawned;
    out.exited = w.exited;
    out.removed = w.removed;
    out.active = w.active;
    out.scheduled = w.scheduled;
    out.groups = static_cast<uint32_t>(s.world().groupCount());
    out.finished = s.world().finished() ? 1 : 0;
    out.recording = s.recording() ? 1 : 0;
    out.last_exit_time = w.lastExitTime;
    out.mean_walking_speed = w.meanWalkingSpeed();
    out.agent_steps = w.agentSteps;
    *out_stats = out;
    return THRONG_OK;
  });
}

throng_status throng_world_state_hash(throng_world* world, uint64_t* out_hash) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_state_hash", lease);
    if (out_hash == nullptr) return nullArgument("throng_world_state_hash", "out_hash");
    *out_hash = lease.session().world().stateHash();
    return THRONG_OK;
  });
}

throng_status throng_world_agents(throng_world* world, const throng_agent_arrays* arrays, size_t* out_count) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_agents", lease);
    if (arrays == nullptr) return nullArgument("throng_world_agents", "arrays");
    if (out_count == nullptr) return nullArgument("throng_world_agents", "out_count");
    const sim::Frame& f = lease.session().frame();
    *out_count = f.size();
    if (f.size() > arrays->capacity) {
      return fail(THRONG_ERROR_BUFFER_TOO_SMALL, "throng_world_agents: " + std::to_string(f.size()) +
                                                     " agents present, capacity " + std::to_string(arrays->capacity));
    }
    copyAgents(lease.session(), f, *arrays);
    return THRONG_OK;
  });
}

throng_status throng_world_group(throng_world* world, const char* population, uint32_t index, uint32_t* out_group) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_group", lease);
    if (population == nullptr) return nullArgument("throng_world_group", "population");
    if (out_group == nullptr) return nullArgument("throng_world_group", "out_group");
    const sim::World& w = lease.session().world();
    const sim::GroupId g = w.group(population, index);
    if (g.isNull()) {
      return fail(THRONG_ERROR_NOT_FOUND, "throng_world_group: no group " + std::to_string(index) + " in population '" +
                                              population + "' (not spawned yet, or no such population)");
    }
    *out_group = w.groupInfo(g)->id;
    return THRONG_OK;
  });
}

throng_status throng_world_guide(throng_world* world, uint32_t group, double x, double y) {
  return guarded([&] { return guide(world, group, x, y, std::nullopt); });
}

throng_status throng_world_guide_at_height(throng_world* world, uint32_t group, double x, double y, double height) {
  return guarded([&] { return guide(world, group, x, y, height); });
}

throng_status throng_world_release(throng_world* world, uint32_t group) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_release", lease);
    sim::World& w = lease.session().world();
    if (!w.release(w.groupById(group))) {
      return fail(THRONG_ERROR_NOT_FOUND, "throng_world_release: no group with id " + std::to_string(group));
    }
    return THRONG_OK;
  });
}

throng_status throng_world_insert_crowd(throng_world* world, const char* json, const char* source, uint32_t* out_index,
                                        char** out_diagnostics) {
  return guarded([&] {
    if (out_diagnostics != nullptr) *out_diagnostics = nullptr;
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_insert_crowd", lease);
    if (json == nullptr) return nullArgument("throng_world_insert_crowd", "json");
    return insertCrowd(lease.session(), json, source != nullptr ? source : "<crowd>", out_index, out_diagnostics);
  });
}

throng_status throng_world_insert_crowd_file(throng_world* world, const char* path, uint32_t* out_index,
                                             char** out_diagnostics) {
  return guarded([&] {
    if (out_diagnostics != nullptr) *out_diagnostics = nullptr;
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_insert_crowd_file", lease);
    if (path == nullptr) return nullArgument("throng_world_insert_crowd_file", "path");
    auto text = readText(path);
    if (!text) return refuse(text.errors(), out_diagnostics);
    return insertCrowd(lease.session(), text.value(), path, out_index, out_diagnostics);
  });
}

throng_status throng_world_remove_crowd(throng_world* world, const char* id) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_remove_crowd", lease);
    if (id == nullptr) return nullArgument("throng_world_remove_crowd", "id");
    if (!lease.session().world().removeCrowd(id)) {
      return fail(THRONG_ERROR_NOT_FOUND, std::string("throng_world_remove_crowd: no crowd '") + id +
                                              "' to remove (unknown, or already removed)");
    }
    return THRONG_OK;
  });
}

throng_status throng_world_set_exit_open(throng_world* world, const char* id, int32_t open) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_set_exit_open", lease);
    if (id == nullptr) return nullArgument("throng_world_set_exit_open", "id");
    if (!lease.session().world().setExitOpen(id, open != 0)) {
      return fail(THRONG_ERROR_NOT_FOUND, std::string("throng_world_set_exit_open: no exit '") + id +
                                              "' (no point of kind \"exit\" has this id)");
    }
    return THRONG_OK;
  });
}

throng_status throng_world_exit_is_wall(throng_world* world, const char* id, int32_t* out_is_wall) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_exit_is_wall", lease);
    if (id == nullptr) return nullArgument("throng_world_exit_is_wall", "id");
    if (out_is_wall == nullptr) return nullArgument("throng_world_exit_is_wall", "out_is_wall");
    *out_is_wall = lease.session().world().exitIsWall(id) ? 1 : 0;
    return THRONG_OK;
  });
}

// The C kinds are the engine's (throng/sim/frame.hpp), value for value.
static_assert(THRONG_EVENT_REUNITED == static_cast<int>(throng::sim::EventKind::Reunited));
static_assert(THRONG_EVENT_EXIT_CHOSEN == static_cast<int>(throng::sim::EventKind::ExitChosen));
static_assert(THRONG_EVENT_WAYPOINT_CHOSEN == static_cast<int>(throng::sim::EventKind::WaypointChosen));
static_assert(THRONG_EVENT_INCAPACITATED == static_cast<int>(throng::sim::EventKind::Incapacitated));

const char* throng_event_kind_name(uint32_t kind) {
  if (kind > THRONG_EVENT_INCAPACITATED) return "unknown";
  return throng::recording::eventKindName(static_cast<sim::EventKind>(kind));
}

throng_status throng_world_events(throng_world* world, throng_event* events, size_t capacity, size_t* out_count) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_events", lease);
    if (out_count == nullptr) return nullArgument("throng_world_events", "out_count");
    if (events == nullptr && capacity > 0) return nullArgument("throng_world_events", "events (with capacity > 0)");
    Session& s = lease.session();
    const std::size_t batch = 256;
    sim::Event buffer[batch];
    std::size_t copied = 0;
    while (copied < capacity) {
      const std::size_t n = s.takeEvents(buffer, std::min(batch, capacity - copied));
      if (n == 0) break;
      for (std::size_t i = 0; i < n; ++i) {
        const sim::Event& e = buffer[i];
        events[copied + i] = throng_event{e.tick, static_cast<double>(e.tick) * s.desc().dt, e.agent,
                                          static_cast<uint32_t>(e.kind), e.a, e.b};
      }
      copied += n;
    }
    *out_count = copied;
    return THRONG_OK;
  });
}

throng_status throng_world_pending_events(throng_world* world, size_t* out_count) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_pending_events", lease);
    if (out_count == nullptr) return nullArgument("throng_world_pending_events", "out_count");
    *out_count = lease.session().pendingEvents();
    return THRONG_OK;
  });
}

throng_status throng_world_record(throng_world* world, const char* path, double fps, int32_t force) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_record", lease);
    if (path == nullptr) return nullArgument("throng_world_record", "path");
    if (!std::isfinite(fps)) return notFinite("throng_world_record", "fps", fps);
    if (fps <= 0) return fail(THRONG_ERROR_INVALID_ARGUMENT, "throng_world_record: fps must be > 0 [Hz], got " + std::to_string(fps));
    Session& s = lease.session();
    if (s.recording()) return fail(THRONG_ERROR_WRONG_STATE, "throng_world_record: already recording");
    if (s.world().stats().tick != 0) {
      return fail(THRONG_ERROR_WRONG_STATE, "throng_world_record: only before the first tick (the world is at tick " +
                                                std::to_string(s.world().stats().tick) + ")");
    }
    const core::Status opened = s.record(path, fps, force != 0);
    if (!opened) return refuse(opened.errors(), nullptr);
    return THRONG_OK;
  });
}

throng_status throng_world_record_close(throng_world* world, uint64_t* out_frames) {
  return guarded([&] {
    const WorldLease lease(world);
    if (lease.status() != THRONG_OK) return leaseFailed("throng_world_record_close", lease);
    Session& s = lease.session();
    if (!s.recording()) return fail(THRONG_ERROR_WRONG_STATE, "throng_world_record_close: not recording");
    std::uint64_t frames = 0;
    const core::Status closed = s.closeRecording(frames);
    if (out_frames != nullptr) *out_frames = frames;
    if (!closed) return fail(THRONG_ERROR_IO, "throng_world_record_close: " + core::formatAll(closed.errors()));
    return THRONG_OK;
  });
}

}  // extern "C"
