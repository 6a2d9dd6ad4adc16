// _throng — the native half of `import throng` (docs/python.md): scenarios loaded and validated by the
// CLI's own loader (diagnostics raise throng.ScenarioError), the Simulation (World + TaskSystem +
// optional Recorder, stepped exactly as `throng run` steps it), the agent state of a tick as
// read-only numpy arrays that share the frame's memory (no copy), events, and run-time crowd
// control (guide, release, insert and remove crowds). The pure-Python half (recordings as pandas
// frames, PedPy-style analysis) is in python/throng/.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
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
namespace {

/// throng.ScenarioError (a ValueError), created when the module is loaded.
PyObject* gScenarioError = nullptr;

py::dict diagnosticDict(const core::Diagnostic& d) {
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
[[noreturn]] void raiseScenarioError(const core::Diagnostics& diagnostics) {
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

const char* modeName(sim::AgentMode mode) {
  switch (mode) {
    case sim::AgentMode::Walking: return "walking";
    case sim::AgentMode::Waiting: return "waiting";
    case sim::AgentMode::Acting: return "acting";
  }
  return "unknown";
}

/// One tick's agent state; its arrays are read-only views of the frame (kept alive by them).
struct AgentState {
  sim::FramePtr frame;
};

/// A read-only 1-D numpy array over `data` (n values) that keeps `frame` alive.
template <typename T>
py::array view(const sim::FramePtr& frame, const T* data, std::size_t n) {
  auto* keep = new sim::FramePtr(frame);
  py::capsule owner(keep, [](void* p) { delete static_cast<sim::FramePtr*>(p); });
  py::array_t<T> array({static_cast<py::ssize_t>(n)}, {static_cast<py::ssize_t>(sizeof(T))}, data, owner);
  array.attr("setflags")(py::arg("write") = false);
  return std::move(array);
}

struct SimulationOptions {
  std::optional<std::uint64_t> seed;
  int threads = 1;
  std::optional<std::string> record;
  double fps = 10.0;
  bool force = false;
  std::optional<double> duration;
};

void checkFinite(double value, const char* name) {
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
    auto world = sim::World::create(desc_, loaded_->navmesh);
    if (!world) raiseScenarioError(world.errors());
    world_ = std::move(world).value();
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

  void removeCrowd(const std::string& id) {
    usable();
    if (!world_->removeCrowd(id)) throw py::key_error("no crowd '" + id + "' to remove (unknown, or already removed)");
  }

  [[nodiscard]] double time() const { return world_->stats().time; }
  [[nodiscard]] std::uint64_t tickCount() const { return world_->stats().tick; }
  [[nodiscard]] bool finished() const { return world_->finished(); }
  [[nodiscard]] std::uint64_t stateHash() const { return world_->stateHash(); }
  [[nodiscard]] std::uint64_t seed() const { return desc_.seed; }
  [[nodiscard]] double dt() const { return desc_.dt; }
  [[nodiscard]] double duration() const { return desc_.duration; }
  [[nodiscard]] std::uint64_t stride() const { return stride_; }

 private:
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
    if (world_->stats().tick % stride_ == 0) record(world_->takeFrame());
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
};

void bindScenario(py::module_& m) {
  py::class_<Scenario>(m, "Scenario", "A validated scenario (docs/scenario-format.md). Load with Scenario.load(path), "
                                      "Scenario.from_json(text) or Scenario.from_dict(d).")
      .def_static("load", &Scenario::load, py::arg("path"),
                  "Reads and validates a scenario file (JSON, or glTF with throng extras); raises ScenarioError "
                  "listing every problem with file:line:column and JSON pointer.")
      .def_static("from_json", &Scenario::fromJson, py::arg("text"), py::arg("source") = "<string>",
                  "Validates scenario JSON text; `source` names it in diagnostics and is the directory clip paths "
                  "are relative to.")
      .def_property_readonly("name", [](const Scenario& s) { return s.desc().name; })
      .def_property_readonly("seed", [](const Scenario& s) { return s.desc().seed; }, "the scenario's random seed")
      .def_property_readonly("duration", [](const Scenario& s) { return s.desc().duration; }, "simulated time [s]")
      .def_property_readonly("dt", [](const Scenario& s) { return s.desc().dt; }, "tick length [s]")
      .def_property_readonly("json", [](const Scenario& s) { return s.loaded->text; }, "the scenario text as read")
      .def_property_readonly("populations", [](const Scenario& s) {
        std::vector<std::string> ids;
        for (const auto& p : s.desc().populations) ids.push_back(p.id);
        return ids;
      }, "population ids, in order")
      .def_property_readonly("points", [](const Scenario& s) {
        std::vector<std::string> ids;
        for (const auto& p : s.desc().points) ids.push_back(p.id);
        return ids;
      }, "point ids, in order")
      .def_property_readonly("models", [](const Scenario& s) {
        std::vector<std::string> names;
        for (const auto& p : s.desc().populations) names.emplace_back(sim::modelInfo(p.model.kind).name);
        return names;
      }, "the operational model of each population")
      .def("__repr__", [](const Scenario& s) {
        return "<throng.Scenario '" + s.desc().name + "': " + std::to_string(s.desc().populations.size()) + " populations, " +
               std::to_string(s.desc().points.size()) + " points>";
      });
}

void bindAgentState(py::module_& m) {
  py::class_<AgentState>(m, "AgentState",
                         "The agents present at one tick, as read-only numpy arrays that share the frame's memory "
                         "(no copy). They stay valid, and unchanged, after later steps: each is a snapshot of its tick.")
      .def_property_readonly("tick", [](const AgentState& a) { return a.frame->tick; })
      .def_property_readonly("time", [](const AgentState& a) { return a.frame->time; }, "[s]")
      .def("__len__", [](const AgentState& a) { return a.frame->size(); })
      .def_property_readonly("id", [](const AgentState& a) { return view(a.frame, a.frame->ids.data(), a.frame->size()); },
                             "stable agent ids (spawn order), ascending (uint32)")
      .def_property_readonly("x", [](const AgentState& a) { return view(a.frame, a.frame->posX.data(), a.frame->size()); }, "[m] (float32)")
      .def_property_readonly("y", [](const AgentState& a) { return view(a.frame, a.frame->posY.data(), a.frame->size()); }, "[m] (float32)")
      .def_property_readonly("z", [](const AgentState& a) -> py::object {
        if (a.frame->posZ.empty()) {  // a flat world: zeros
          py::array_t<float> zeros(static_cast<py::ssize_t>(a.frame->size()));
          std::fill_n(zeros.mutable_data(), a.frame->size(), 0.0f);
          return std::move(zeros);
        }
        return view(a.frame, a.frame->posZ.data(), a.frame->size());
      }, "height [m] on a multi-level world (float32; a new array of zeros on a flat one)")
      .def_property_readonly("vx", [](const AgentState& a) { return view(a.frame, a.frame->velX.data(), a.frame->size()); }, "[m/s] (float32)")
      .def_property_readonly("vy", [](const AgentState& a) { return view(a.frame, a.frame->velY.data(), a.frame->size()); }, "[m/s] (float32)")
      .def_property_readonly("ori_x", [](const AgentState& a) { return view(a.frame, a.frame->oriX.data(), a.frame->size()); }, "unit heading (float32)")
      .def_property_readonly("ori_y", [](const AgentState& a) { return view(a.frame, a.frame->oriY.data(), a.frame->size()); }, "unit heading (float32)")
      .def_property_readonly("mode", [](const AgentState& a) {
        return view(a.frame, reinterpret_cast<const std::uint8_t*>(a.frame->mode.data()), a.frame->size());
      }, "0 walking, 1 waiting, 2 acting (uint8)")
      .def_property_readonly("clip", [](const AgentState& a) { return view(a.frame, a.frame->clip.data(), a.frame->size()); },
                             "motion clip playing: index into the scenario's clips (uint16)")
      .def_property_readonly("phase", [](const AgentState& a) { return view(a.frame, a.frame->phase.data(), a.frame->size()); },
                             "position in that clip, [0, 1) (float32)");
}

void bindSimulation(py::module_& m) {
  py::class_<Simulation>(m, "Simulation", py::dynamic_attr(),
                         "A running world. Simulation(scenario, seed=None, threads=1, record=None, fps=10, force=False, "
                         "duration=None): seed and duration override the scenario's; record names a SQLite file written "
                         "exactly as `throng run --out` writes it (fps frames per second). Same seed, same trajectories "
                         "as the CLI, for any thread count. Use as a context manager, or call close().")
      .def(py::init([](const Scenario& scenario, std::optional<std::uint64_t> seed, int threads, std::optional<std::string> record,
                       double fps, bool force, std::optional<double> duration) {
             return std::make_unique<Simulation>(scenario, SimulationOptions{seed, threads, std::move(record), fps, force, duration});
           }),
           py::arg("scenario"), py::kw_only(), py::arg("seed") = py::none(), py::arg("threads") = 1, py::arg("record") = py::none(),
           py::arg("fps") = 10.0, py::arg("force") = false, py::arg("duration") = py::none())
      .def("step", &Simulation::step, py::arg("n") = 1,
           "Advances n ticks of dt seconds (fewer if everyone leaves); ValueError once finished.")
      .def("run", &Simulation::run, py::arg("until") = py::none(),
           "Steps until `until` seconds (default: the duration) or until everyone has left, ending on a recorded "
           "tick as `throng run` does. Returns the simulated time [s].")
      .def("close", &Simulation::close, "Flushes and closes the recording; no stepping afterwards.")
      .def("__enter__", [](Simulation& s) -> Simulation& { return s; }, py::return_value_policy::reference)
      .def("__exit__", [](Simulation& s, const py::object&, const py::object&, const py::object&) { s.close(); })
      .def("agents", &Simulation::agents, "The agents present now (AgentState: zero-copy read-only numpy arrays).")
      .def("events", &Simulation::events,
           "Events since the last call, oldest first, as dicts: tick, time [s], agent (stable id), kind (spawn, exit, "
           "goal_reached, action_start, ...; docs/python.md), a, b.")
      .def("agent", &Simulation::agent, py::arg("id"), "What one agent is doing (dict); KeyError if absent.")
      .def("group", &Simulation::group, py::arg("population"), py::arg("index"),
           "Stable id of group `index` (0-based) of a population; KeyError if it has not spawned.")
      .def("group_info", &Simulation::groupInfo, py::arg("id"), "Members, leader and state of a group (dict).")
      .def("guide", &Simulation::guide, py::arg("group"), py::arg("x"), py::arg("y"), py::arg("height") = py::none(),
           "The group follows (x, y) [m] (an avatar, say) from the next tick until release(group).")
      .def("release", &Simulation::release, py::arg("group"), "Guidance ends; the group resumes its goals.")
      .def("insert_crowd", &Simulation::insertCrowd, py::arg("text"), py::arg("source") = "<crowd>",
           "Queues a crowd (JSON text of a throng-crowd/1 file; docs/scenario-format.md) for the next tick; "
           "returns its index. ScenarioError lists every problem.")
      .def("remove_crowd", &Simulation::removeCrowd, py::arg("id"), "Its agents leave at the next tick.")
      .def_property_readonly("stats", &Simulation::stats, "running totals (dict)")
      .def_property_readonly("time", &Simulation::time, "simulated time [s]")
      .def_property_readonly("tick", &Simulation::tickCount)
      .def_property_readonly("finished", &Simulation::finished, "every agent has left and none is scheduled")
      .def_property_readonly("state_hash", &Simulation::stateHash,
                             "hash of every agent's id, position and velocity bits (the CLI's state_hash)")
      .def_property_readonly("seed", &Simulation::seed)
      .def_property_readonly("dt", &Simulation::dt, "[s]")
      .def_property_readonly("duration", &Simulation::duration, "[s]")
      .def_property_readonly("frame_stride", &Simulation::stride, "ticks between recorded frames");
}

}  // namespace
}  // namespace throng::python

PYBIND11_MODULE(_throng, m) {
  m.doc() = "throng's native module; use `import throng` (docs/python.md).";
  throng::python::gScenarioError = PyErr_NewExceptionWithDoc(
      "throng.ScenarioError", "A scenario, crowd or recording path was refused; .diagnostics lists every problem as dicts.",
      PyExc_ValueError, nullptr);
  m.attr("ScenarioError") = py::handle(throng::python::gScenarioError);
  throng::python::bindScenario(m);
  throng::python::bindAgentState(m);
  throng::python::bindSimulation(m);
}
