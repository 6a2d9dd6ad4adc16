// _throng — the native half of `import throng` (docs/python.md): the Python bindings of scenarios
// loaded and validated by the CLI's own loader (diagnostics raise throng.ScenarioError), the
// Simulation (simulation.hpp: stepped exactly as `throng run` steps it, events, run-time crowd
// control, exits opened and closed), the agent state as numpy arrays without copies
// (agent_views.hpp: AgentState snapshots, AgentView of the live columns, refused once stale with
// throng.StaleViewError). The pure-Python half (recordings as pandas frames, PedPy-style analysis)
// is in python/throng/.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "agent_views.hpp"
#include "simulation.hpp"
#include "throng/core/simd.hpp"
#include "throng/sim/models.hpp"

namespace py = pybind11;

namespace throng::python {
namespace {

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

void bindAgentView(py::module_& m) {
  using C = sim::AgentColumns;
  py::class_<AgentView>(m, "AgentView",
                        "The agents present now, read in place from the engine's own columns: read-only numpy arrays "
                        "that copy nothing. Valid until the simulation steps, runs or closes; then every access raises "
                        "StaleViewError (arrays taken before stay readable memory but no longer describe the agents: "
                        "take sim.view() anew after each step). sim.agents() gives snapshots that stay valid instead.")
      .def_property_readonly("valid", &AgentView::valid, "False once the simulation stepped, ran or closed")
      .def_property_readonly("tick", &AgentView::tick, "the tick the view was taken at")
      .def_property_readonly("time", &AgentView::time, "[s]")
      .def("__len__", &AgentView::size)
      .def_property_readonly("id", [](const AgentView& v) { return v.array(&C::id); }, "stable agent ids (spawn order), ascending (uint32)")
      .def_property_readonly("group", [](const AgentView& v) { return v.array(&C::group); }, "stable group ids (uint32)")
      .def_property_readonly("x", [](const AgentView& v) { return v.array(&C::posX); }, "[m] (float32)")
      .def_property_readonly("y", [](const AgentView& v) { return v.array(&C::posY); }, "[m] (float32)")
      .def_property_readonly("z", &AgentView::z, "height [m] on a multi-level world (float32; a new array of zeros on a flat one)")
      .def_property_readonly("vx", [](const AgentView& v) { return v.array(&C::velX); }, "[m/s] (float32)")
      .def_property_readonly("vy", [](const AgentView& v) { return v.array(&C::velY); }, "[m/s] (float32)")
      .def_property_readonly("ori_x", [](const AgentView& v) { return v.array(&C::oriX); }, "unit heading (float32)")
      .def_property_readonly("ori_y", [](const AgentView& v) { return v.array(&C::oriY); }, "unit heading (float32)")
      .def_property_readonly("mode", &AgentView::mode, "0 walking, 1 waiting, 2 acting (uint8)")
      .def_property_readonly("clip", [](const AgentView& v) { return v.array(&C::clip); },
                             "motion clip playing: index into the scenario's clips (uint16)")
      .def_property_readonly("phase", [](const AgentView& v) { return v.array(&C::phase); }, "position in that clip, [0, 1) (float32)")
      .def("__repr__", [](const AgentView& v) {
        return "<throng.AgentView of tick " + std::to_string(v.tick()) + (v.valid() ? "" : " (stale)") + ">";
      });
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
      .def("agents", &Simulation::agents,
           "The agents present now as a snapshot (AgentState: read-only numpy arrays over a copy the engine made "
           "for this tick; they stay valid after later steps).")
      .def("view", [](py::object self) { return AgentView(std::move(self)); },
           "The agents present now, read in place (AgentView: read-only numpy arrays over the engine's own columns, "
           "nothing copied), valid until the next step, run or close; StaleViewError after that.")
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
      .def("set_exit_open", &Simulation::setExitOpen, py::arg("id"), py::arg("open"),
           "Closes (open=False) or opens an exit from the next tick (a door on an event): nobody leaves by a "
           "closed exit, groups choosing among exits re-route, a fixed goal waits at the door. KeyError if `id` "
           "is no exit.")
      .def("exit_is_wall", &Simulation::exitIsWall, py::arg("id"),
           "Whether closing the exit `id` makes its floor a wall: True for every exit with floor in its region "
           "(an exit a crowd inserted at run time brought is cut into the navmesh when it first closes); False for "
           "an exit with no floor in its region, and for an id that is no exit.")
      .def("remove_agents", &Simulation::removeAgents, py::arg("ids"),
           "These agents (stable ids: an int, a list, a numpy array) leave at the next tick, each with an exit event "
           "(a = b = 4294967295); their groups go on with the others (a removed leader hands over to the lowest id "
           "left). ValueError naming every id not present now, listed twice or already queued; nothing is removed then.")
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
  throng::python::gStaleViewError = PyErr_NewExceptionWithDoc(
      "throng.StaleViewError", "An AgentView (sim.view()) was used after the simulation stepped, ran or closed; take a new one.",
      PyExc_RuntimeError, nullptr);
  m.attr("StaleViewError") = py::handle(throng::python::gStaleViewError);
  m.def(
      "simd_path", [] { return std::string(throng::core::simdPathName(throng::core::simdPath())); },
      "The vector path of the engine's hot loops in this process: 'avx2' or 'portable' (the environment variable "
      "THRONG_SIMD picks one before the module is imported; every path gives the same trajectories).");
  throng::python::bindScenario(m);
  throng::python::bindAgentState(m);
  throng::python::bindAgentView(m);
  throng::python::bindSimulation(m);
}

