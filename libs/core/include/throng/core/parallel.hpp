// throng::core::TaskSystem — the threads a World runs on, injected by the application (after
// Box2D's enqueueTask and Jolt's JobSystem). parallelFor splits [0, n) into fixed chunks of
// `grain`; each index is visited exactly once, and because phases only write the row of the index
// they visit, the result never depends on how chunks land on threads.
#pragma once
#include <cstddef>
#include <functional>
#include <memory>

namespace throng::core {

class TaskSystem {
 public:
  /// threads = 1 runs everything on the calling thread; 0 means all hardware threads.
  explicit TaskSystem(int threads = 1);
  ~TaskSystem();
  TaskSystem(const TaskSystem&) = delete;
  TaskSystem& operator=(const TaskSystem&) = delete;

  [[nodiscard]] int threads() const { return threads_; }

  /// Calls body(begin, end) over fixed chunks [k*grain, min(n,(k+1)*grain)).
  void parallelFor(std::size_t n, std::size_t grain,
                   const std::function<void(std::size_t begin, std::size_t end)>& body) const;

  /// Runs `first` and `second` side by side when there is more than one thread (`first` may call
  /// parallelFor: the thread that finishes `second` joins in), one after the other otherwise;
  /// returns when both have. The two must not write what the other reads.
  void invoke(const std::function<void()>& first, const std::function<void()>& second) const;

  /// Index of the calling worker in [0, threads()), for per-thread scratch (query objects,
  /// buffers). Scratch must never change results, only where they are computed.
  [[nodiscard]] int workerIndex() const;

  /// Number of fixed chunks parallelFor(n, grain) uses; reductions keep one slot per chunk and
  /// combine them in chunk order, so sums are identical for any thread count.
  static std::size_t chunkCount(std::size_t n, std::size_t grain) { return grain == 0 ? 0 : (n + grain - 1) / grain; }

  /// Caps the chunk size callers ask for through grain(): 0 (the default) leaves their grains as
  /// they are. [limit] >= 0 [rows]. Smaller chunks spread a small crowd over every thread, which the
  /// determinism tests use to split the work of a few hundred agents among 8 threads; results never
  /// depend on the thread count, whatever the limit.
  void setGrainLimit(std::size_t limit) { grainLimit_ = limit; }
  [[nodiscard]] std::size_t grainLimit() const { return grainLimit_; }
  /// The chunk size to use for a loop that wants `wanted` rows per chunk: min(wanted, limit).
  [[nodiscard]] std::size_t grain(std::size_t wanted) const {
    return grainLimit_ != 0 && grainLimit_ < wanted ? grainLimit_ : wanted;
  }

 private:
  int threads_;
  std::size_t grainLimit_ = 0;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng::core
