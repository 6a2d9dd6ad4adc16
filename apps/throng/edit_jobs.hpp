// `throng edit`'s worker threads: each API request that checks or simulates runs on its own thread
// (at most kMaxJobs at once) with a cancel flag that a watchdog raises when the client hangs up or
// the job's wall-clock limit passes. stop() cancels every job and joins them (before the transport
// goes: each holds its HttpResponder).
#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <thread>

#include "throng/transport/transport.hpp"

namespace throng::cli::edit {

/// What a job's work polls: `cancel` (the io::LoadOptions::cancel shape) and why it was raised.
struct JobFlags {
  std::atomic<int> cancel{0};
  std::atomic<bool> timedOut{false};
};

class Jobs {
 public:
  static constexpr std::size_t kMaxJobs = 4;

  Jobs() : watchdog_([this] { watch(); }) {}
  ~Jobs() { stop(); }
  Jobs(const Jobs&) = delete;
  Jobs& operator=(const Jobs&) = delete;

  /// Runs `work` on a new thread; false (nothing started) when kMaxJobs are running or stopping.
  bool launch(transport::HttpResponder responder, std::chrono::milliseconds limit,
              std::function<void(const JobFlags&)> work) {
    std::lock_guard lock(mutex_);
    reap();
    if (stopping_ || jobs_.size() >= kMaxJobs) return false;
    auto job = std::make_shared<Job>(std::move(responder), std::chrono::steady_clock::now() + limit);
    job->thread = std::thread([job, work = std::move(work)] {
      work(job->flags);
      job->done.store(true);
    });
    jobs_.push_back(std::move(job));
    return true;
  }

  /// Cancels every job and waits for them and the watchdog.
  void stop() {
    {
      std::lock_guard lock(mutex_);
      if (stopping_) return;
      stopping_ = true;
      for (auto& job : jobs_) job->flags.cancel.store(1);
    }
    wake_.notify_all();
    watchdog_.join();
    for (auto& job : jobs_) job->thread.join();
    jobs_.clear();
  }

 private:
  struct Job {
    Job(transport::HttpResponder r, std::chrono::steady_clock::time_point d) : responder(std::move(r)), deadline(d) {}
    transport::HttpResponder responder;
    std::chrono::steady_clock::time_point deadline;
    JobFlags flags;
    std::atomic<bool> done{false};
    std::thread thread;
  };

  /// Joins finished jobs (mutex held).
  void reap() {
    for (auto it = jobs_.begin(); it != jobs_.end();) {
      if ((*it)->done.load()) {
        (*it)->thread.join();
        it = jobs_.erase(it);
      } else {
        ++it;
      }
    }
  }

  void watch() {
    std::unique_lock lock(mutex_);
    while (!stopping_) {
      const auto now = std::chrono::steady_clock::now();
      for (auto& job : jobs_) {
        if (job->flags.cancel.load() != 0) continue;
        if (now > job->deadline) job->flags.timedOut.store(true);
        if (now > job->deadline || job->responder.cancelled()) job->flags.cancel.store(1);
      }
      wake_.wait_for(lock, std::chrono::milliseconds(20));
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::list<std::shared_ptr<Job>> jobs_;
  bool stopping_ = false;
  std::thread watchdog_;  // last: started once the rest is built
};

}  // namespace throng::cli::edit
