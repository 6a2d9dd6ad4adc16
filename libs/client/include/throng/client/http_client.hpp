// throng::client::httpRequest — one blocking HTTP/1.1 request on a fresh connection (tests,
// health checks, fetching a recording). Reads and writes a socket.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

#include "throng/core/result.hpp"

namespace throng::client {

struct HttpReply {
  unsigned status = 0;
  std::string contentType;
  std::string body;                 ///< empty for HEAD
  std::uint64_t contentLength = 0;  ///< from the header (HEAD included)
};

/// A request body and its Content-Type (POST).
struct HttpBody {
  std::string text;
  std::string contentType = "application/json";
};

/// `method` is "GET", "HEAD", "POST", ...; `target` is sent as is (no encoding), so tests can
/// send malformed targets.
core::Result<HttpReply> httpRequest(const std::string& host, std::uint16_t port, const std::string& method,
                                    const std::string& target, std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));
/// The same with a body (Content-Length set; POST always has one, maybe empty).
core::Result<HttpReply> httpRequest(const std::string& host, std::uint16_t port, const std::string& method,
                                    const std::string& target, const HttpBody& body,
                                    std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));

}  // namespace throng::client
