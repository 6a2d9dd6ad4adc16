// Tests for the POST hook of libs/transport/src/http_session.cpp (TransportOptions::postHandler,
// HttpResponder) through a real socket: an answer now and one later from another thread, a request
// the hook does not take (404), a throwing hook (500), a responder dropped unanswered (500), a body
// over the limit (413), keep-alive after an answer, and a client that hangs up cancelling the work.
#include <gtest/gtest.h>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "test_handler.hpp"
#include "throng/client/http_client.hpp"

namespace throng::transport::test {
using client::HttpBody;
using client::HttpReply;
using client::httpRequest;
namespace {
using namespace std::chrono_literals;

class HttpPostTest : public ::testing::Test {
 protected:
  void SetUp() override {
    TransportOptions options = testOptions();
    options.maxPostBytes = 1000;
    options.postHandler = [this](HttpRequest request, HttpResponder responder) { return onPost(std::move(request), responder); };
    auto started = Transport::start(options, handler_);
    ASSERT_TRUE(started.ok()) << core::formatAll(started.errors());
    transport_ = std::move(started.value());
  }
  void TearDown() override {
    for (std::thread& worker : workers_) worker.join();
    transport_.reset();
  }

  bool onPost(HttpRequest request, const HttpResponder& responder) {
    if (request.target == "/echo") {
      responder.respond({200, "text/plain", request.contentType + "|" + request.body, {}});
    } else if (request.target == "/later") {
      workers_.emplace_back([responder, body = request.body] {
        std::this_thread::sleep_for(50ms);
        responder.respond({201, "application/json", "{\"later\":\"" + body + "\"}", {}});
      });
    } else if (request.target == "/throw") {
      throw std::runtime_error("hook failed");
    } else if (request.target == "/drop") {
      return true;  // the last responder goes here, unanswered
    } else if (request.target == "/slow") {
      workers_.emplace_back([this, responder] {
        const auto until = std::chrono::steady_clock::now() + 5s;
        while (!responder.cancelled() && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(5ms);
        slowCancelled_ = responder.cancelFlag().load() != 0;
        slowDone_ = true;
        responder.respond({200, "text/plain", "too late", {}});
      });
    } else {
      return false;
    }
    return true;
  }

  HttpReply post(const std::string& target, const std::string& body) {
    auto reply = httpRequest("127.0.0.1", transport_->httpPort(), "POST", target, HttpBody{body, "application/json"});
    EXPECT_TRUE(reply.ok()) << (reply.ok() ? "" : core::formatAll(reply.errors()));
    return reply.ok() ? reply.value() : HttpReply{};
  }

  TestHandler handler_;
  std::unique_ptr<Transport> transport_;
  std::vector<std::thread> workers_;  // touched on the transport thread only (one io thread)
  std::atomic<bool> slowCancelled_{false};
  std::atomic<bool> slowDone_{false};
};

TEST_F(HttpPostTest, AnswersNowAndLater) {
  const HttpReply echo = post("/echo", "{\"a\":1}");
  EXPECT_EQ(echo.status, 200u);
  EXPECT_EQ(echo.body, "application/json|{\"a\":1}");
  const HttpReply later = post("/later", "x");
  EXPECT_EQ(later.status, 201u);
  EXPECT_EQ(later.contentType, "application/json");
  EXPECT_EQ(later.body, "{\"later\":\"x\"}");
}

TEST_F(HttpPostTest, NotTakenThrowingAndUnanswered) {
  EXPECT_EQ(post("/nope", "").status, 404u);
  const HttpReply thrown = post("/throw", "");
  EXPECT_EQ(thrown.status, 500u);
  EXPECT_NE(thrown.body.find("hook failed"), std::string::npos) << thrown.body;
  const HttpReply dropped = post("/drop", "");
  EXPECT_EQ(dropped.status, 500u);
  EXPECT_NE(dropped.body.find("not answered"), std::string::npos) << dropped.body;
  // Other methods are still refused, and the refusal names POST now.
  const auto refused = httpRequest("127.0.0.1", transport_->httpPort(), "PUT", "/echo");
  ASSERT_TRUE(refused.ok());
  EXPECT_EQ(refused.value().status, 405u);
  EXPECT_NE(refused.value().body.find("POST"), std::string::npos);
}

TEST_F(HttpPostTest, BodyOverTheLimitIs413) {
  const HttpReply big = post("/echo", std::string(1001, 'x'));
  EXPECT_EQ(big.status, 413u);
  EXPECT_NE(big.body.find("1000 bytes"), std::string::npos) << big.body;
  EXPECT_EQ(post("/echo", std::string(1000, 'x')).status, 200u);
}

TEST_F(HttpPostTest, KeepAliveAfterALaterAnswer) {
  namespace asio = boost::asio;
  namespace http = boost::beast::http;
  asio::io_context ioc;
  asio::ip::tcp::socket socket(ioc);
  socket.connect({asio::ip::make_address("127.0.0.1"), transport_->httpPort()});
  boost::beast::flat_buffer buffer;
  for (const char* target : {"/later", "/echo", "/later"}) {
    http::request<http::string_body> req{http::verb::post, target, 11};
    req.set(http::field::host, "localhost");
    req.body() = "k";
    req.prepare_payload();
    http::write(socket, req);
    http::response<http::string_body> res;
    http::read(socket, buffer, res);
    EXPECT_LT(res.result_int(), 300u) << target;
    EXPECT_TRUE(res.keep_alive()) << target;
  }
}

TEST_F(HttpPostTest, HangingUpCancelsTheResponder) {
  namespace asio = boost::asio;
  namespace http = boost::beast::http;
  {
    asio::io_context ioc;
    asio::ip::tcp::socket socket(ioc);
    socket.connect({asio::ip::make_address("127.0.0.1"), transport_->httpPort()});
    http::request<http::string_body> req{http::verb::post, "/slow", 11};
    req.set(http::field::host, "localhost");
    req.body() = "{}";
    req.prepare_payload();
    http::write(socket, req);
    std::this_thread::sleep_for(100ms);
    socket.close();
  }
  const auto until = std::chrono::steady_clock::now() + 4s;
  while (!slowDone_ && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(5ms);
  EXPECT_TRUE(slowDone_.load());
  EXPECT_TRUE(slowCancelled_.load());
}

}  // namespace
}  // namespace throng::transport::test
