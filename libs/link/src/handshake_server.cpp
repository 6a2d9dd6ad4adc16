// throng::link::HandshakeServer — the UNIX-socket handshake that passes the segment's name to a
// host (start mode (c), docs/integration.md). Reads and writes the socket only.
#include "throng/link/handshake_server.hpp"

#include <cerrno>
#include <charconv>
#include <cstring>

#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "throng/throng_link.h"

namespace throng::link {
namespace {

core::Diagnostic problem(const std::string& path, std::string what, std::string expected = {}) {
  core::Diagnostic d;
  d.source = path;
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}

void sendAll(int fd, const std::string& text) {
  std::size_t sent = 0;
  while (sent < text.size()) {
    const ssize_t n = ::send(fd, text.data() + sent, text.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;
    sent += static_cast<std::size_t>(n);
  }
}

}  // namespace

core::Result<std::unique_ptr<HandshakeServer>> HandshakeServer::start(const std::string& path,
                                                                      const std::string& segment, bool force,
                                                                      Report report) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof address.sun_path) {
    return problem(path, "socket path is empty or too long",
                   "1 to " + std::to_string(sizeof address.sun_path - 1) + " bytes");
  }
  std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    if (!force) return problem(path, "a file of this name exists already", "a new path, or --force to replace it");
    if (!S_ISSOCK(st.st_mode)) return problem(path, "exists and is not a socket; not replacing it", "a socket path");
    ::unlink(path.c_str());
  }
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return problem(path, std::string("socket: ") + std::strerror(errno));
  if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 || ::listen(fd, 8) != 0) {
    const int e = errno;
    ::close(fd);
    return problem(path, std::string("cannot listen: ") + std::strerror(e));
  }
  auto server = std::unique_ptr<HandshakeServer>(new HandshakeServer());
  server->path_ = path;
  server->segment_ = segment;
  server->report_ = std::move(report);
  server->listenFd_ = fd;
  server->thread_ = std::thread([s = server.get()] { s->serve(); });
  return server;
}

HandshakeServer::~HandshakeServer() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (listenFd_ >= 0) ::close(listenFd_);
  ::unlink(path_.c_str());
}

void HandshakeServer::serve() {
  while (!stop_) {
    pollfd p{listenFd_, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    const int fd = ::accept4(listenFd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) continue;
    answer(fd);
    ::close(fd);
  }
}

void HandshakeServer::answer(int fd) {
  sendAll(fd, std::string(THRONG_LINK_HANDSHAKE) + " " + std::to_string(THRONG_LINK_VERSION) + " " + segment_ + "\n");
  // The host's line, within 2 s.
  std::string line;
  char buffer[256];
  while (line.find('\n') == std::string::npos && line.size() < 256) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 2000) <= 0) {
      if (report_) report_(true, "a host connected to " + path_ + " but did not answer the handshake within 2 s");
      return;
    }
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) {
      if (report_) report_(true, "a host connected to " + path_ + " and left during the handshake");
      return;
    }
    line.append(buffer, static_cast<std::size_t>(n));
  }
  line = line.substr(0, line.find('\n'));
  const std::string prefix = std::string(THRONG_LINK_HANDSHAKE_HOST) + " ";
  unsigned version = 0;
  const bool wellFormed =
      line.starts_with(prefix) &&
      std::from_chars(line.data() + prefix.size(), line.data() + line.size(), version).ec == std::errc{};
  if (!wellFormed) {
    const std::string why = "expected \"" + prefix + "<version>\", got \"" + line.substr(0, 80) + "\"";
    sendAll(fd, "REFUSED " + why + "\n");
    if (report_) report_(true, "host refused: " + why);
    return;
  }
  if (version != THRONG_LINK_VERSION) {
    const std::string why = "host speaks link version " + std::to_string(version) + ", this crowd speaks version " +
                            std::to_string(THRONG_LINK_VERSION);
    sendAll(fd, "REFUSED " + why + "\n");
    if (report_) report_(true, "host refused: " + why);
    return;
  }
  sendAll(fd, "OK\n");
  if (report_) report_(false, "handshake on " + path_ + ": segment " + segment_ + " sent");
}

}  // namespace throng::link
