// The agent state as numpy arrays without copies (python/src/module.cpp binds them): AgentState, a
// tick's snapshot over a frame the engine copied, valid for as long as it is held; AgentView, the
// World's own columns read in place, refused once the simulation steps (its arrays keep their
// memory alive: the Simulation, and the buffers the World retired since).
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <memory>
#include <span>
#include <string>

#include "simulation.hpp"
#include "throng/sim/world.hpp"

namespace throng::python {

/// A read-only 1-D numpy array over `data` (n values) whose base is `keep`: numpy keeps `keep` alive
/// as long as the array or anything derived from it, and cannot make the array writable (its base
/// is no writable buffer).
template <typename T>
py::array readOnlyArray(const T* data, std::size_t n, const py::object& keep) {
  py::array_t<T> array({static_cast<py::ssize_t>(n)}, {static_cast<py::ssize_t>(sizeof(T))}, data, keep);
  array.attr("setflags")(py::arg("write") = false);
  return std::move(array);
}

/// A frame's column as a read-only numpy array (AgentState) that keeps the frame alive.
template <typename T>
py::array view(const sim::FramePtr& frame, const T* data, std::size_t n) {
  auto* keep = new sim::FramePtr(frame);
  return readOnlyArray(data, n, py::capsule(keep, [](void* p) { delete static_cast<sim::FramePtr*>(p); }));
}

/// What an AgentView's arrays hold on to: the Python Simulation (so the World and its columns live
/// on) and the buffers of their stretch, should the World retire them later.
struct ViewKeep {
  py::object simulation;
  std::shared_ptr<RetiredColumns> retired;
};

/// The agents present now, read in place from the World's columns (no copy), valid until the
/// simulation steps or closes: every access after that raises throng.StaleViewError. Its arrays are
/// read-only and their memory is never freed while Python holds them (ViewKeep, RetiredColumns).
class AgentView {
 public:
  explicit AgentView(py::object simulation)
      : sim_(viewable(simulation)), generation_(sim_->generation()), columns_(sim_->columns()), tick_(sim_->tickCount()),
        time_(sim_->time()) {
    keep_ = py::capsule(new ViewKeep{std::move(simulation), sim_->retired()},
                        [](void* p) { delete static_cast<ViewKeep*>(p); });
  }

  [[nodiscard]] bool valid() const { return !sim_->closed() && sim_->generation() == generation_; }
  [[nodiscard]] std::uint64_t tick() const { return tick_; }
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] std::size_t size() const {
    check();
    return columns_.size();
  }
  /// One column as a read-only numpy array sharing the World's memory.
  template <typename T>
  [[nodiscard]] py::array array(std::span<const T> sim::AgentColumns::*column) const {
    check();
    const std::span<const T> c = columns_.*column;
    return readOnlyArray(c.data(), c.size(), keep_);
  }
  [[nodiscard]] py::array mode() const {
    check();
    return readOnlyArray(reinterpret_cast<const std::uint8_t*>(columns_.mode.data()), columns_.size(), keep_);
  }
  [[nodiscard]] py::object z() const {
    check();
    if (columns_.posZ.empty()) {  // a flat world: zeros
      py::array_t<float> zeros(static_cast<py::ssize_t>(columns_.size()));
      std::fill_n(zeros.mutable_data(), columns_.size(), 0.0f);
      return std::move(zeros);
    }
    return readOnlyArray(columns_.posZ.data(), columns_.size(), keep_);
  }

 private:
  static Simulation* viewable(const py::object& simulation) {
    auto* sim = &simulation.cast<Simulation&>();
    sim->checkViewable();
    return sim;
  }
  void check() const {
    if (valid()) return;
    const std::string why = sim_->closed() ? "the simulation was closed"
                                           : "the simulation has stepped since (now tick " + std::to_string(sim_->tickCount()) + ")";
    PyErr_SetString(gStaleViewError, ("this AgentView of tick " + std::to_string(tick_) + " is stale: " + why +
                                      "; take a new one with sim.view() after each step")
                                         .c_str());
    throw py::error_already_set();
  }

  Simulation* sim_;  ///< kept alive by keep_
  std::uint64_t generation_;
  sim::AgentColumns columns_;
  std::uint64_t tick_;
  double time_;
  py::object keep_;  ///< capsule of a ViewKeep: the base of every array
};

}  // namespace throng::python
