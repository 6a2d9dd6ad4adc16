// throng::client::httpRequest — one HTTP/1.1 request on a fresh connection, with a deadline.
#include "throng/client/http_client.hpp"

#include <utility>

#include "throng/net/asio.hpp"
#include "client_io.hpp"

namespace throng::client {
using namespace detail;

core::Result<HttpReply> httpRequest(const std::string& host, std::uint16_t port, const std::string& method,
                                    const std::string& target, std::chrono::milliseconds timeout) {
  return httpRequest(host, port, method, target, HttpBody{}, timeout);
}

core::Result<HttpReply> httpRequest(const std::string& host, std::uint16_t port, const std::string& method,
                                    const std::string& target, const HttpBody& body, std::chrono::milliseconds timeout) {
  asio::io_context ioc;
  beast::tcp_stream stream(ioc);
  tcp::resolver resolver(ioc);
  http::request<http::string_body> req;
  req.method_string(method);
  req.target(target);
  req.version(11);
  req.set(http::field::host, host + ":" + std::to_string(port));
  req.set(http::field::connection, "close");
  if (!body.contentType.empty()) req.set(http::field::content_type, body.contentType);
  req.body() = body.text;
  if (!body.text.empty() || method == "POST") req.prepare_payload();
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.body_limit(256 << 20);
  parser.skip(method == "HEAD");

  bool done = false;
  error_code result;
  auto fail = [&](error_code ec) {
    done = true;
    result = ec;
  };
  stream.expires_after(timeout);
  resolver.async_resolve(host, std::to_string(port), [&](error_code ec, tcp::resolver::results_type endpoints) {
    if (ec) return fail(ec);
    stream.async_connect(endpoints, [&](error_code ec2, const tcp::endpoint&) {
      if (ec2) return fail(ec2);
      http::async_write(stream, req, [&](error_code ec3, std::size_t) {
        if (ec3) return fail(ec3);
        http::async_read(stream, buffer, parser, [&](error_code ec4, std::size_t) { fail(ec4); });
      });
    });
  });
  runUntil(ioc, [&] { return done; }, timeout + std::chrono::milliseconds(500));
  core::Diagnostic d;
  d.source = "http://" + host + ":" + std::to_string(port) + target;
  if (!done) {
    resolver.cancel();
    stream.close();
    runUntil(ioc, [&] { return done; }, std::chrono::milliseconds(1000));
    d.what = "request timed out";
    return d;
  }
  if (result) {
    d.what = method + " failed: " + result.message();
    return d;
  }
  auto res = parser.release();
  HttpReply reply;
  reply.status = res.result_int();
  reply.contentType = std::string(res[http::field::content_type]);
  if (auto length = res[http::field::content_length]; !length.empty()) {
    try {
      reply.contentLength = std::stoull(std::string(length));
    } catch (...) {
      reply.contentLength = 0;
    }
  }
  reply.body = std::move(res.body());
  error_code ignored;
  stream.socket().shutdown(tcp::socket::shutdown_both, ignored);
  return reply;
}

}  // namespace throng::client
