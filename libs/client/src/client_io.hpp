// throng::client::detail::runUntil — drives a client's private io_context until a condition
// holds or a deadline passes (the blocking clients are built on it).
#pragma once
#include <chrono>

#include "throng/net/asio.hpp"

namespace throng::client::detail {
using namespace throng::net;  // asio::, beast::, tcp, udp, error_code

/// Runs handlers until `done()` or `timeout`; returns done(). Never busy-waits: returns when the
/// context has no work left. A zero timeout runs only the handlers that are ready.
template <class Done>
bool runUntil(asio::io_context& ioc, Done&& done, std::chrono::milliseconds timeout) {
  if (timeout.count() <= 0) {
    // No waiting: run whatever is ready (run_one_until with a past deadline would run nothing).
    if (ioc.stopped()) ioc.restart();
    ioc.poll();
    return done();
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (ioc.stopped()) ioc.restart();
    if (ioc.run_one_until(deadline) == 0) return done();
  }
  return true;
}

}  // namespace throng::client::detail
