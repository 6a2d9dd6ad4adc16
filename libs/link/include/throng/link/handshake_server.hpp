// throng::link::HandshakeServer — start mode (c) of the shared-memory link: listens on a UNIX
// domain socket and tells each host that connects the segment's name and the layout version:
//   crowd → host   "THRONG-LINK <version> <segment name>\n"
//   host  → crowd  "THRONG-LINK-HOST <version>\n"
//   crowd → host   "OK\n", or "REFUSED <why>\n" when the versions differ
// then closes the connection; the host opens the segment by name. Runs on its own thread; creates
// the socket file and removes it when destroyed.
#pragma once
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "throng/core/result.hpp"

namespace throng::link {

class HandshakeServer {
 public:
  /// Called on the server's thread for each handshake: `refused` and a sentence for people.
  using Report = std::function<void(bool refused, const std::string& message)>;

  /// Listens on `path`. An existing file is refused unless `force` (then it is replaced).
  static core::Result<std::unique_ptr<HandshakeServer>> start(const std::string& path, const std::string& segment,
                                                              bool force, Report report);
  ~HandshakeServer();  ///< stops the thread, closes and removes the socket file
  HandshakeServer(const HandshakeServer&) = delete;
  HandshakeServer& operator=(const HandshakeServer&) = delete;

 private:
  HandshakeServer() = default;
  void serve();
  void answer(int fd);

  std::string path_, segment_;
  Report report_;
  int listenFd_ = -1;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace throng::link
