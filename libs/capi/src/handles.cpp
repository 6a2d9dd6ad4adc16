// The registry of live C API handles (handles.hpp).
#include "handles.hpp"

namespace throng::capi {

Registry& Registry::instance() {
  // Never destroyed: a handle freed from another static's destructor at exit still finds it.
  static Registry* const registry = new Registry();
  return *registry;
}

void Registry::add(const throng_scenario* s) {
  const std::lock_guard lock(mutex_);
  scenarios_.insert(s);
}

void Registry::add(const throng_world* w) {
  const std::lock_guard lock(mutex_);
  worlds_.insert(w);
}

std::shared_ptr<const io::LoadedScenario> Registry::scenario(const throng_scenario* s) {
  const std::lock_guard lock(mutex_);
  return scenarios_.count(s) ? s->loaded : nullptr;
}

bool Registry::removeScenario(const throng_scenario* s) {
  const std::lock_guard lock(mutex_);
  return scenarios_.erase(s) == 1;
}

throng_status Registry::acquire(throng_world* w) {
  const std::lock_guard lock(mutex_);
  if (!worlds_.count(w)) return THRONG_ERROR_BAD_HANDLE;
  if (w->busy) return THRONG_ERROR_BUSY;
  w->busy = true;
  return THRONG_OK;
}

void Registry::releaseWorld(throng_world* w) {
  const std::lock_guard lock(mutex_);
  w->busy = false;
}

throng_status Registry::removeWorld(throng_world* w) {
  const std::lock_guard lock(mutex_);
  if (!worlds_.count(w)) return THRONG_ERROR_BAD_HANDLE;
  if (w->busy) return THRONG_ERROR_BUSY;
  worlds_.erase(w);
  return THRONG_OK;
}

}  // namespace throng::capi
