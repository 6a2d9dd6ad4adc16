// Tests for libs/transport/src/http_session.cpp through a real socket: static files with their
// Content-Type, index.html, 404, traversal refused, HEAD, 405, /health, the dynamic hook,
// keep-alive, a malformed request, and a bind error.
#include <gtest/gtest.h>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <fstream>
#include <random>

#include "test_handler.hpp"
#include "throng/client/http_client.hpp"

namespace throng::transport::test {
using client::HttpReply;
using client::httpRequest;
namespace {
namespace fs = std::filesystem;

class HttpTest : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = fs::temp_directory_path() / ("throng_http_" + std::to_string(std::random_device{}()));
    fs::create_directories(base_ / "www" / "assets");
    std::ofstream(base_ / "www" / "index.html") << "<!doctype html><title>viewer</title>";
    std::ofstream(base_ / "www" / "assets" / "app.js") << "console.log(1);";
    std::ofstream(base_ / "www" / "assets" / "style.css") << "body{}";
    std::ofstream(base_ / "www" / "assets" / "model.glb") << "glTF";
    std::ofstream(base_ / "www" / "assets" / "m.wasm") << "wasm";
    std::ofstream(base_ / "www" / "space name.json") << "{}";
    std::ofstream(base_ / "secret.txt") << "secret";
    TransportOptions options = testOptions();
    options.staticRoot = base_ / "www";
    options.httpHandler = [](std::string_view target) -> std::optional<HttpResponse> {
      if (target == "/api/info") return HttpResponse{200, "application/json", "{\"agents\":3}", {}};
      return std::nullopt;
    };
    auto started = Transport::start(options, handler_);
    ASSERT_TRUE(started.ok()) << core::formatAll(started.errors());
    transport_ = std::move(started.value());
  }
  void TearDown() override {
    transport_.reset();
    fs::remove_all(base_);
  }
  HttpReply get(const std::string& target, const std::string& method = "GET") {
    auto reply = httpRequest("127.0.0.1", transport_->httpPort(), method, target);
    EXPECT_TRUE(reply.ok()) << (reply.ok() ? "" : core::formatAll(reply.errors()));
    return reply.ok() ? reply.value() : HttpReply{};
  }

  fs::path base_;
  TestHandler handler_;
  std::unique_ptr<Transport> transport_;
};

TEST_F(HttpTest, ServesFilesWithContentTypes) {
  const HttpReply index = get("/");
  EXPECT_EQ(index.status, 200u);
  EXPECT_EQ(index.contentType, "text/html; charset=utf-8");
  EXPECT_EQ(index.body, "<!doctype html><title>viewer</title>");
  EXPECT_EQ(get("/index.html").body, index.body);
  const HttpReply js = get("/assets/app.js?v=3");
  EXPECT_EQ(js.status, 200u);
  EXPECT_EQ(js.contentType, "text/javascript; charset=utf-8");
  EXPECT_EQ(js.body, "console.log(1);");
  EXPECT_EQ(get("/assets/style.css").contentType, "text/css; charset=utf-8");
  EXPECT_EQ(get("/assets/model.glb").contentType, "model/gltf-binary");
  EXPECT_EQ(get("/assets/m.wasm").contentType, "application/wasm");
  EXPECT_EQ(get("/space%20name.json").contentType, "application/json");
}

TEST_F(HttpTest, NotFoundAndTraversal) {
  const HttpReply missing = get("/nope.js");
  EXPECT_EQ(missing.status, 404u);
  EXPECT_FALSE(missing.body.empty());
  for (const std::string target : {"/../secret.txt", "/assets/../../secret.txt", "/%2e%2e/secret.txt",
                                   "/assets/%2E%2E%2F%2E%2E%2Fsecret.txt", "/..%5csecret.txt", "/%00"}) {
    const HttpReply reply = get(target);
    EXPECT_EQ(reply.status, 400u) << target;
    EXPECT_EQ(reply.body.find("secret"), std::string::npos) << target;
  }
}

TEST_F(HttpTest, HeadMethodsHealthAndHook) {
  const HttpReply head = get("/assets/app.js", "HEAD");
  EXPECT_EQ(head.status, 200u);
  EXPECT_EQ(head.contentLength, 15u);
  EXPECT_TRUE(head.body.empty());
  EXPECT_EQ(get("/", "POST").status, 405u);
  EXPECT_EQ(get("/", "DELETE").status, 405u);
  const HttpReply health = get("/health");
  EXPECT_EQ(health.status, 200u);
  EXPECT_EQ(health.contentType, "application/json");
  EXPECT_NE(health.body.find("\"status\":\"ok\""), std::string::npos);
  const HttpReply info = get("/api/info");
  EXPECT_EQ(info.status, 200u);
  EXPECT_EQ(info.body, "{\"agents\":3}");
  EXPECT_EQ(get("/api/other").status, 404u);
}

TEST_F(HttpTest, KeepAliveServesSeveralRequestsOnOneConnection) {
  namespace asio = boost::asio;
  namespace http = boost::beast::http;
  asio::io_context ioc;
  asio::ip::tcp::socket socket(ioc);
  socket.connect({asio::ip::make_address("127.0.0.1"), transport_->httpPort()});
  boost::beast::flat_buffer buffer;
  for (const char* target : {"/health", "/assets/app.js", "/nope"}) {
    http::request<http::empty_body> req{http::verb::get, target, 11};
    req.set(http::field::host, "localhost");
    http::write(socket, req);
    http::response<http::string_body> res;
    http::read(socket, buffer, res);
    EXPECT_TRUE(res.keep_alive()) << target;
  }
  EXPECT_EQ(transport_->totals().httpRequests, 3u);
}

TEST_F(HttpTest, MalformedRequestGets400) {
  namespace asio = boost::asio;
  asio::io_context ioc;
  asio::ip::tcp::socket socket(ioc);
  socket.connect({asio::ip::make_address("127.0.0.1"), transport_->httpPort()});
  const std::string junk = "GET / HTTP/1.1\r\nHost: x\r\nContent-Length: banana\r\n\r\n";
  asio::write(socket, asio::buffer(junk));
  std::string reply;
  boost::system::error_code ec;
  char chunk[512];
  for (std::size_t n; (n = socket.read_some(asio::buffer(chunk), ec)) > 0 && !ec;) reply.append(chunk, n);
  EXPECT_EQ(reply.rfind("HTTP/1.1 400", 0), 0u) << reply;
}

TEST(HttpBind, PortInUseIsADiagnostic) {
  TestHandler handler;
  auto first = Transport::start(testOptions(), handler);
  ASSERT_TRUE(first.ok());
  TransportOptions options = testOptions();
  options.httpPort = first.value()->httpPort();
  auto second = Transport::start(options, handler);
  ASSERT_FALSE(second.ok());
  const std::string text = core::formatAll(second.errors());
  EXPECT_NE(text.find("127.0.0.1:" + std::to_string(options.httpPort)), std::string::npos) << text;
  EXPECT_NE(text.find("in use"), std::string::npos) << text;

  TransportOptions bad = testOptions();
  bad.bindAddress = "not-an-address";
  bad.maxDatagramBytes = 70000;
  auto third = Transport::start(bad, handler);
  ASSERT_FALSE(third.ok());
  EXPECT_EQ(third.errors().size(), 1u);  // option errors first; the address is checked on bind

  TransportOptions tiny = testOptions();
  tiny.udpFragmentBytes = 10;  // no room for a Fragment header and payload
  auto fourth = Transport::start(tiny, handler);
  ASSERT_FALSE(fourth.ok());
  EXPECT_NE(core::formatAll(fourth.errors()).find("udpFragmentBytes"), std::string::npos);
}

}  // namespace
}  // namespace throng::transport::test
