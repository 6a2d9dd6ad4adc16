// The C API's handles: what a throng_scenario and a throng_world hold, and the registry of live
// handles that lets every entry point tell a handle it made from NULL, garbage or a freed one
// without dereferencing it, and keeps one thread at a time inside a world (THRONG_ERROR_BUSY).
#pragma once
#include <memory>
#include <mutex>
#include <unordered_set>

#include "session.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/throng.h"

struct throng_scenario {
  std::shared_ptr<const throng::io::LoadedScenario> loaded;
};

struct throng_world {
  std::unique_ptr<throng::capi::Session> session;
  bool busy = false;  ///< a thread is inside a call on it (guarded by the registry's mutex)
};

namespace throng::capi {

/// Every live handle, by address. Thread-safe.
class Registry {
 public:
  static Registry& instance();

  void add(const throng_scenario* s);
  void add(const throng_world* w);
  /// The scenario's data, or nullptr when `s` is not a live scenario.
  std::shared_ptr<const io::LoadedScenario> scenario(const throng_scenario* s);
  /// Forgets `s`; false when it is not a live scenario.
  bool removeScenario(const throng_scenario* s);
  /// Marks `w` busy: THRONG_OK, THRONG_ERROR_BAD_HANDLE or THRONG_ERROR_BUSY.
  throng_status acquire(throng_world* w);
  void releaseWorld(throng_world* w);
  /// Forgets `w` (OK), unless it is not live (BAD_HANDLE) or busy (BUSY).
  throng_status removeWorld(throng_world* w);

 private:
  std::mutex mutex_;
  std::unordered_set<const void*> scenarios_, worlds_;
};

/// A world held for one call: acquired in the constructor, released in the destructor.
class WorldLease {
 public:
  explicit WorldLease(throng_world* w) : world_(w), status_(w ? Registry::instance().acquire(w) : THRONG_ERROR_NULL_ARGUMENT) {}
  ~WorldLease() {
    if (status_ == THRONG_OK) Registry::instance().releaseWorld(world_);
  }
  WorldLease(const WorldLease&) = delete;
  WorldLease& operator=(const WorldLease&) = delete;
  [[nodiscard]] throng_status status() const { return status_; }
  [[nodiscard]] Session& session() const { return *world_->session; }

 private:
  throng_world* world_;
  throng_status status_;
};

}  // namespace throng::capi
