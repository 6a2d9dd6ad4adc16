// TaskSystem over oneTBB: a task_arena limited to the requested thread count, static chunking.
#include "throng/core/parallel.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/parallel_invoke.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>

#include <thread>

namespace throng::core {

struct TaskSystem::Impl {
  // oneTBB caps its workers at the hardware's threads; a caller that asks for more (8 threads on a
  // 2-core machine: the determinism tests, a user's --threads) gets them while this TaskSystem lives.
  explicit Impl(int threads)
      : oversubscribe(threads > tbb::info::default_concurrency()
                          ? std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                                  static_cast<std::size_t>(threads))
                          : nullptr),
        arena(threads) {}
  std::unique_ptr<tbb::global_control> oversubscribe;
  tbb::task_arena arena;
};

TaskSystem::TaskSystem(int threads) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads_ = threads;
  if (threads_ > 1) impl_ = std::make_unique<Impl>(threads_);
}

TaskSystem::~TaskSystem() = default;

void TaskSystem::parallelFor(std::size_t n, std::size_t grain,
                             const std::function<void(std::size_t, std::size_t)>& body) const {
  if (n == 0) return;
  if (grain == 0) grain = 1;
  const std::size_t chunks = chunkCount(n, grain);
  if (!impl_ || chunks == 1) {
    for (std::size_t c = 0; c < chunks; ++c) body(c * grain, std::min(n, (c + 1) * grain));
    return;
  }
  impl_->arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, chunks, 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t c = r.begin(); c < r.end(); ++c) body(c * grain, std::min(n, (c + 1) * grain));
        },
        tbb::simple_partitioner());
  });
}

void TaskSystem::invoke(const std::function<void()>& first, const std::function<void()>& second) const {
  if (!impl_) {
    first();
    second();
    return;
  }
  impl_->arena.execute([&] { tbb::parallel_invoke(first, second); });
}

int TaskSystem::workerIndex() const {
  if (!impl_) return 0;
  const int index = tbb::this_task_arena::current_thread_index();
  return (index < 0 || index >= threads_) ? 0 : index;
}

}  // namespace throng::core
