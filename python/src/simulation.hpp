// The native module's Simulation (python/src/module.cpp binds it): a validated Scenario, the World
// with its threads and optional Recorder stepped exactly as `throng run` steps it, events, run-time
// crowd control, exits opened and closed on events, and what views of the live columns need (a
// generation bumped by every step, the column buffers the World retired). Its Python errors:
// throng.ScenarioError, throng.StaleViewError.
#pragma once
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "throng/core/parallel.hpp"
#include "throng/io/crowd_loader.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/recording/recorder.hpp"
#include "throng/sim/models.hpp"
#include "throng/sim/world.hpp"

namespace py = pybind11;

namespace throng::python {

/// throng.ScenarioError (a ValueError), created when the module is loaded.
inline PyObject* gScenarioError = nullptr;
/// throng.StaleViewError (a RuntimeError): an AgentView used after the simulation changed.
inline PyObject* gStaleViewError = nullptr;

inline py::dict diagnosticDict(const core::Diagnostic& d) {
  py::dict out;
  out["source"] = d.source;
  out["line"] = d.line;
  out["column"] = d.column;
  out["pointer"] = d.pointer;
  out["what"] = d.what;
  out["expected"] = d.expected;
  out["hint"] = d.hint;
  out["text"] = d.format();
  return out;
}

/// Raises throng.ScenarioError: the message lists every diagnostic; `.diagnostics` holds them as dicts.
[[noreturn]] inline void raiseScenarioError(const core::Diagnostics& diagnostics) {
  py::list list;
  for (const core::Diagnostic& d : diagnostics) list.append(diagnosticDict(d));
  py::object error = py::reinterpret_borrow<py::object>(gScenarioError)(core::formatAll(diagnostics));
  error.attr("diagnostics") = list;
  PyErr_SetObject(gScenarioError, error.ptr());
  throw py::error_already_set();
}

/// A validated scenario (immutable once loaded; the Simulation copies what it changes).
struct Scenario {
  std::shared_ptr<const io::LoadedScenario> loaded;

  static Scenario load(const std::string& path) {
    auto result = io::loadScenarioFile(path);
    if (!result) raiseScenarioError(result.errors());
    return Scenario{std::make_shared<const io::LoadedScenario>(std::move(result).value())};
  }
  static Scenario fromJson(const std::string& text, const std::string& source) {
    auto result = io::parseScenario(text, source);
    if (!result) raiseScenarioError(result.errors());
    return Scenario{std::make_shared<const io::LoadedScenario>(std::move(result).value())};
  }
  [[nodiscard]] const sim::ScenarioDesc& desc() const { return loaded->desc; }
};

inline const char* modeName(sim::AgentMode mode) {
  switch (mode) {
    case sim::AgentMode::Walking: return "walking";
    case sim::AgentMode::Waiting: return "waiting";
    case sim::AgentMode::Acting: return "acting";
  }
  return "unknown";
}


/// Column buffers the World retired while views into them may still be alive (World::keepRetiredColumns).
/// One per stretch of ticks between two retirements; every array made in that stretch holds it.
struct RetiredColumns {
  std::vector<std::shared_ptr<const void>> buffers;
};


/// One tick's agent state; its arrays are read-only views of the frame (kept alive by them).
struct AgentState {
  sim::FramePtr frame;
};

struct SimulationOptions {
  std::optional<std::uint64_t> seed;
  int threads = 1;
  std::optional<std::string> record;
  double fps = 10.0;
  bool force = false;
  std::optional<double> duration;
};

inline void checkFinite(double value, const char* name) {
  if (!std::isfinite(value)) throw py::value_error(std::string(name) + " must be a finite number, got " + std::to_string(value));
}

/// The world, its threads and its recording, stepped as `throng run` steps them: frame 0 is the
/// state before the first tick, then every stride-th tick is recorded with the events since.
class Simulation {
 public:
  Simulation(const Scenario& scenario, const SimulationOptions& options) : loaded_(scenario.loaded) {
    if (options.threads < 0) throw py::value_error("threads must be >= 0 (0: every hardware thread), got " + std::to_string(options.threads));
    if (!(options.fps > 0.0) || !std::isfinite(options.fps)) throw py::value_error("fps must be a positive finite number");
    desc_ = loaded_->desc;
    if (options.seed) desc_.seed = *options.seed;
    if (options.duration) {
      checkFinite(*options.duration, "duration");
      if (*options.duration <= 0.0) throw py::value_error("duration must be > 0 [s]");
      desc_.duration = static_cast<float>(*options.duration);
    }
    const double ratio = 1.0 / (options.fps * desc_.dt);
    stride_ = static_cast<std::uint64_t>(std::max(1.0, std::round(ratio)));
    if (options.record) openRecording(*options.record, options);
    // AgentView promises ascending ids (docs/python.md): rows stay in id order (sim::RowOrder).
    desc_.rowOrder = sim::RowOrder::Id;
    auto world = sim::World::create(desc_, loaded_->navmesh);
    if (!world) raiseScenarioError(world.errors());
    world_ = std::move(world).value();
    world_->keepRetiredColumns(true);  // AgentView's arrays may outlive a step: their memory must not be freed
    tasks_ = std::make_unique<core::TaskSystem>(options.threads);
    record(world_->takeFrame());  // frame 0
  }

  ~Simulation() {
    try {
      close();
    } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor reports nothing; close() raised it already if called
    }
  }

  /// Advances n ticks (the GIL is released meanwhile).
  void step(std::int64_t n) {
    usable();
    if (n < 0) throw py::value_error("step(n): n must be >= 0, got " + std::to_string(n));
    if (world_->finished()) throw py::value_error("the simulation is finished: every agent has left (check sim.finished)");
    if (n == 0) return;
    const Stepping stepping(*this);
    py::gil_scoped_release release;
    for (std::int64_t i = 0; i < n && !world_->finished(); ++i) tick();
  }

  /// Steps on until `until` seconds (default: the scenario's duration) or until everyone has left,
  /// stopping, like `throng run`, on a recorded tick. Returns the simulated time.
  double run(std::optional<double> until) {
    usable();
    const double end = until.value_or(desc_.duration);
    checkFinite(end, "until");
    const auto endTick = static_cast<std::uint64_t>(std::max(0LL, std::llround(end / desc_.dt)));
    {
      const Stepping stepping(*this);
      py::gil_scoped_release release;
      while (true) {
        const std::uint64_t t = world_->stats().tick;
        if (t % stride_ == 0 && (world_->finished() || t >= endTick)) break;
        tick();
      }
    }
    return world_->stats().time;
  }

  /// Flushes and closes the recording (completed); the simulation cannot step after it.
  void close() {
    if (closed_) return;
    closed_ = true;
    ++generation_;
    if (recorder_) {
      const core::Status status = recorder_->close(true);
      recorder_.reset();
      if (!status) throw py::value_error("the recording failed: " + core::formatAll(status.errors()));
    }
  }

  AgentState agents() {
    usable();
    sim::FramePtr frame = world_->takeFrame();
    keep(frame);
    return AgentState{std::move(frame)};
  }

  /// The events since the last call (drained), as dicts.
  py::list events() {
    usable();
    keep(world_->takeFrame());
    py::list out;
    const double dt = desc_.dt;
    for (const sim::Event& e : pyEvents_) {
      py::dict d;
      d["tick"] = e.tick;
      d["time"] = static_cast<double>(e.tick) * dt;
      d["agent"] = e.agent;
      d["kind"] = recording::eventKindName(e.kind);  // the names recordings use
      d["a"] = e.a;
      d["b"] = e.b;
      out.append(std::move(d));
    }
    pyEvents_.clear();
    return out;
  }

  [[nodiscard]] py::dict stats() const {
    const sim::WorldStats& s = world_->stats();
    py::dict d;
    d["tick"] = s.tick;
    d["time"] = s.time;
    d["spawned"] = s.spawned;
    d["exited"] = s.exited;
    d["removed"] = s.removed;
    d["active"] = s.active;
    d["scheduled"] = s.scheduled;
    d["last_exit_time"] = s.lastExitTime < 0 ? py::object(py::none()) : py::object(py::float_(s.lastExitTime));
    d["mean_walking_speed"] = s.meanWalkingSpeed();
    d["agent_steps"] = s.agentSteps;
    return d;
  }

  [[nodiscard]] std::uint32_t group(const std::string& population, std::uint32_t index) const {
    const sim::GroupId g = world_->group(population, index);
    if (g.isNull()) throw py::key_error("no group " + std::to_string(index) + " in population '" + population + "' (not spawned yet, or no such population)");
    return world_->groupInfo(g)->id;
  }

  [[nodiscard]] py::dict groupInfo(std::uint32_t id) const {
    const auto info = world_->groupInfo(world_->groupById(id));
    if (!info) throw py::key_error("no group with id " + std::to_string(id));
    py::dict d;
    d["id"] = info->id;
    d["population"] = desc_.populations.size() > info->population ? desc_.populations[info->population].id : std::string();
    d["members"] = info->members;
    d["leader"] = info->leader == 0xffffffffu ? py::object(py::none()) : py::object(py::int_(info->leader));
    d["waiting"] = info->waiting;
    d["guided"] = info->guided;
    return d;
  }

  [[nodiscard]] py::dict agent(std::uint32_t id) const {
    const auto info = world_->agentInfo(id);
    if (!info) throw py::key_error("no agent with id " + std::to_string(id) + " in the world (not spawned yet, or left)");
    py::dict d;
    d["id"] = info->id;
    d["group"] = info->group;
    d["population"] = world_->desc().populations[info->population].id;
    d["mode"] = modeName(info->mode);
    d["state"] = info->state;
    d["position"] = py::make_tuple(info->position.x, info->position.y);
    d["target"] = py::make_tuple(info->target.x, info->target.y);
    d["speed"] = info->speed;
    d["guided"] = info->guided;
    return d;
  }

  void guide(std::uint32_t group, double x, double y, std::optional<double> height) {
    usable();
    checkFinite(x, "x");
    checkFinite(y, "y");
    const sim::GroupId g = world_->groupById(group);
    const core::Vec2 p{static_cast<float>(x), static_cast<float>(y)};
    bool ok = false;
    if (height) {
      checkFinite(*height, "height");
      ok = world_->guide(g, p, static_cast<float>(*height));
    } else {
      ok = world_->guide(g, p);
    }
    if (!ok) throw py::key_error("no group with id " + std::to_string(group));
  }

  void release(std::uint32_t group) {
    usable();
    if (!world_->release(world_->groupById(group))) throw py::key_error("no group with id " + std::to_string(group));
  }

  std::uint32_t insertCrowd(const std::string& text, const std::string& source) {
    usable();
    auto crowd = io::parseCrowd(text, source, *world_);
    if (!crowd) raiseScenarioError(crowd.errors());
    auto index = world_->insertCrowd(crowd.value());
    if (!index) raiseScenarioError(index.errors());
    return index.value();
  }

  /// Queues the removal of these agents (stable ids; an int or any iterable of ints, numpy arrays
  /// included) for the next tick. ValueError naming every bad id, with nothing queued.
  void removeAgents(const py::handle& ids) {
    usable();
    std::vector<std::uint32_t> list;
    std::string bad;
    auto add = [&](const py::handle& item, std::size_t i) {
      const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(item.ptr()));
      if (!index) {
        PyErr_Clear();
        throw py::type_error("remove_agents: ids[" + std::to_string(i) + "] is a " + std::string(py::str(item.get_type().attr("__name__"))) +
                             "; expected an int agent id");
      }
      int overflow = 0;
      const long long id = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
      if (overflow != 0 || id < 0 || id > 0xffffffffLL) {
        bad += "; ids[" + std::to_string(i) + "]: " + std::string(py::str(index)) + " is not an agent id (expected 0 .. 4294967295)";
      }
      list.push_back(static_cast<std::uint32_t>(id));
    };
    if (py::isinstance<py::str>(ids) || py::isinstance<py::bytes>(ids)) throw py::type_error("remove_agents expects agent ids (ints), not a string");
    if (py::isinstance<py::iterable>(ids)) {
      std::size_t i = 0;
      for (const py::handle item : py::reinterpret_borrow<py::iterable>(ids)) add(item, i++);
    } else if (PyIndex_Check(ids.ptr())) {
      add(ids, 0);
    } else {
      throw py::type_error("remove_agents expects an agent id or an iterable of ids (ints), got " +
                           std::string(py::str(ids.get_type().attr("__name__"))));
    }
    if (!bad.empty()) throw py::value_error("remove_agents: " + bad.substr(2));
    const core::Status queued = world_->removeAgents(list);
    if (queued) return;
    std::string what;
    for (const core::Diagnostic& d : queued.errors()) what += "; ids[" + d.pointer.substr(1) + "]: " + d.what;
    throw py::value_error("remove_agents: " + what.substr(2) + " (nothing removed)");
  }

  void removeCrowd(const std::string& id) {
    usable();
    if (!world_->removeCrowd(id)) throw py::key_error("no crowd '" + id + "' to remove (unknown, or already removed)");
  }

  void setExitOpen(const std::string& id, bool open) {
    usable();
    if (!world_->setExitOpen(id, open)) throw py::key_error("no exit '" + id + "' (no point of kind \"exit\" has this id)");
  }

  [[nodiscard]] bool exitIsWall(const std::string& id) const {
    usable();
    return world_->exitIsWall(id);
  }

  [[nodiscard]] double time() const { return world_->stats().time; }
  [[nodiscard]] std::uint64_t tickCount() const { return world_->stats().tick; }
  [[nodiscard]] bool finished() const { return world_->finished(); }
  [[nodiscard]] std::uint64_t stateHash() const { return world_->stateHash(); }
  [[nodiscard]] std::uint64_t seed() const { return desc_.seed; }
  [[nodiscard]] double dt() const { return desc_.dt; }
  [[nodiscard]] double duration() const { return desc_.duration; }
  [[nodiscard]] std::uint64_t stride() const { return stride_; }

  // What an AgentView reads: the live columns, and what keeps them valid.
  /// Bumped before every step or run and by close(): a view of an older generation is stale.
  [[nodiscard]] std::uint64_t generation() const { return generation_.load(); }
  [[nodiscard]] bool stepping() const { return stepping_.load(); }
  [[nodiscard]] bool closed() const { return closed_; }
  [[nodiscard]] sim::AgentColumns columns() const { return world_->agentColumns(); }
  [[nodiscard]] const std::shared_ptr<RetiredColumns>& retired() const { return retired_; }
  void checkViewable() const {
    usable();
    if (stepping()) throw py::value_error("the simulation is stepping in another thread: take the view after step() returns");
  }

 private:
  /// While a step or run is under way (the GIL released): views taken before are stale from its start.
  struct Stepping {
    Simulation& s;
    explicit Stepping(Simulation& sim) : s(sim) {
      ++s.generation_;
      s.stepping_ = true;
    }
    ~Stepping() { s.stepping_ = false; }
    Stepping(const Stepping&) = delete;
    Stepping& operator=(const Stepping&) = delete;
  };
  void usable() const {
    if (closed_) throw py::value_error("the simulation is closed (close() or the end of its with-block)");
  }

  void openRecording(const std::string& path, const SimulationOptions& options) {
    recording::RecordingOptions r;
    r.path = path;
    r.force = options.force;
    r.fps = std::fabs(1.0 / (options.fps * desc_.dt) - static_cast<double>(stride_)) <= 1e-6 / (options.fps * desc_.dt)
                ? options.fps
                : 1.0 / (static_cast<double>(stride_) * desc_.dt);
    r.seed = desc_.seed;
    r.scenarioText = loaded_->text;
    auto opened = recording::Recorder::open(desc_, r);
    if (!opened) raiseScenarioError(opened.errors());
    recorder_ = std::move(opened).value();
  }

  void tick() {
    world_->step(*tasks_);
    keepRetired();
    if (world_->stats().tick % stride_ == 0) record(world_->takeFrame());
  }

  /// Buffers the World retired this tick stay with the views of the stretch that may read them;
  /// freed at once when no view of it is alive (only this Simulation holds it).
  void keepRetired() {
    std::vector<std::shared_ptr<const void>> buffers = world_->takeRetiredColumns();
    if (buffers.empty() || retired_.use_count() == 1) return;
    retired_->buffers = std::move(buffers);
    retired_ = std::make_shared<RetiredColumns>();
  }

  /// A frame taken for Python: its events go to events() and, with the script records, into the
  /// next recorded frame (the recording misses nothing Python looked at first).
  void keep(const sim::FramePtr& frame) {
    pyEvents_.insert(pyEvents_.end(), frame->events.begin(), frame->events.end());
    if (recorder_) carry_.add(*frame);
  }

  void record(sim::FramePtr frame) {
    pyEvents_.insert(pyEvents_.end(), frame->events.begin(), frame->events.end());
    if (!recorder_) return;
    recorder_->push(carry_.merge(std::move(frame)));
  }

  std::shared_ptr<const io::LoadedScenario> loaded_;
  sim::ScenarioDesc desc_;
  std::unique_ptr<sim::World> world_;
  std::unique_ptr<core::TaskSystem> tasks_;
  std::unique_ptr<recording::Recorder> recorder_;
  std::uint64_t stride_ = 1;
  recording::FrameCarry carry_;       ///< what Python's own frames drained, for the next recorded one
  std::vector<sim::Event> pyEvents_;  ///< events not yet handed to events()
  bool closed_ = false;
  std::atomic<std::uint64_t> generation_{0};  ///< see generation()
  std::atomic<bool> stepping_{false};
  std::shared_ptr<RetiredColumns> retired_ = std::make_shared<RetiredColumns>();  ///< this stretch's (keepRetired)
};


}  // namespace throng::python
