// throng::transport::detail::HttpSession — HTTP/1.1 GET/HEAD/POST with keep-alive, and the /ws upgrade.
// Answers: /health (JSON), the dynamic hook, static files, POST through the POST hook (answered
// later, from any thread, through HttpResponder); 400 for a malformed or escaping target, 404,
// 405 for other methods (and POST without a hook), 413 for a POST body over the limit, 503 when
// the peer limit is reached.
#include "http_session.hpp"

#include <exception>
#include <utility>

#include "static_files.hpp"
#include "transport_impl.hpp"
#include "ws_peer.hpp"

namespace throng::transport::detail {
namespace {

constexpr std::size_t kHeaderLimit = 8 * 1024;
constexpr std::size_t kBodyLimit = 64 * 1024;

http::response<http::string_body> textResponse(http::status status, std::string_view contentType,
                                               std::string body, unsigned version, bool keepAlive) {
  http::response<http::string_body> res{status, version};
  res.set(http::field::server, "throng");
  res.set(http::field::content_type, beast::string_view(contentType.data(), contentType.size()));
  res.keep_alive(keepAlive);
  res.body() = std::move(body);
  res.prepare_payload();
  return res;
}

std::string endpointText(const tcp::endpoint& endpoint) {
  const auto address = endpoint.address();
  const std::string host = address.is_v6() ? "[" + address.to_string() + "]" : address.to_string();
  return host + ":" + std::to_string(endpoint.port());
}

}  // namespace

PostState::~PostState() {
  if (!answered.load()) answer(HttpResponse{500, "text/plain", "internal error: the request was not answered\n", {}});
}

void PostState::answer(HttpResponse response) {
  if (answered.exchange(true)) return;
  std::shared_ptr<HttpSession> target = std::move(session);
  if (!target) return;
  asio::post(target->executor_, [target, response = std::move(response)]() mutable {
    target->sendPostAnswer(std::move(response));
  });
}

}  // namespace throng::transport::detail

namespace throng::transport {

HttpResponder::HttpResponder(std::shared_ptr<detail::PostState> state) : state_(std::move(state)) {}

void HttpResponder::respond(HttpResponse response) const { state_->answer(std::move(response)); }

bool HttpResponder::cancelled() const { return state_->cancelled.load() != 0; }

const std::atomic<int>& HttpResponder::cancelFlag() const { return state_->cancelled; }

}  // namespace throng::transport

namespace throng::transport::detail {

HttpSession::HttpSession(TransportImpl& transport, tcp::socket&& socket)
    : transport_(transport), stream_(std::move(socket)), executor_(stream_.get_executor()) {
  error_code ec;
  const auto endpoint = stream_.socket().remote_endpoint(ec);
  remote_ = ec ? std::string("unknown") : endpointText(endpoint);
}

void HttpSession::start() {
  std::weak_ptr<HttpSession> weak = shared_from_this();
  registration_ = transport_.addHttpConnection([weak] {
    if (auto self = weak.lock()) self->requestClose();
  });
  if (transport_.stopping()) {
    finish();
    return;
  }
  doRead();
}

void HttpSession::requestClose() {
  asio::post(executor_, [self = shared_from_this()] { self->finish(); });
}

void HttpSession::doRead() {
  parser_.emplace();
  parser_->header_limit(kHeaderLimit);
  const TransportOptions& options = transport_.options();
  parser_->body_limit(options.postHandler ? options.maxPostBytes : kBodyLimit);
  stream_.expires_after(transport_.options().httpTimeout);
  http::async_read(stream_, buffer_, *parser_, beast::bind_front_handler(&HttpSession::onRead, shared_from_this()));
}

void HttpSession::onRead(error_code ec, std::size_t) {
  if (done_) return;
  if (ec) {
    const error_code endOfStream = http::error::end_of_stream;
    if (ec == http::error::body_limit) {
      send(textResponse(http::status::payload_too_large, "text/plain",
                        "request body too large; the limit is " + std::to_string(transport_.options().maxPostBytes) +
                            " bytes\n",
                        11, false));
      return;
    }
    if (ec.category() == endOfStream.category() && ec != endOfStream) {
      // A malformed request: say so once, then hang up.
      send(textResponse(http::status::bad_request, "text/plain", "bad request\n", 11, false));
      return;
    }
    finish();
    return;
  }
  handle(parser_->release());
}

void HttpSession::handle(http::request<http::string_body>&& req) {
  transport_.countHttpRequest();
  const std::string_view target(req.target().data(), req.target().size());
  if (websocket::is_upgrade(req)) {
    if (targetPath(target) == kWebSocketPath) {
      upgrade(std::move(req));
      return;
    }
    send(textResponse(http::status::not_found, "text/plain", "no WebSocket here; use /ws\n", req.version(), false));
    return;
  }
  const Reply reply{req.version(), req.keep_alive() && !transport_.stopping(), req.method() == http::verb::head};
  const bool posts = static_cast<bool>(transport_.options().postHandler);
  if (posts && req.method() == http::verb::post) {
    handlePost(reply, std::move(req));
    return;
  }
  if (!reply.head && req.method() != http::verb::get) {
    auto res = textResponse(http::status::method_not_allowed, "text/plain",
                            posts ? "method not allowed; expected GET, HEAD or POST\n"
                                  : "method not allowed; expected GET or HEAD\n",
                            reply.version, reply.keepAlive);
    res.set(http::field::allow, posts ? "GET, HEAD, POST" : "GET, HEAD");
    send(std::move(res));
    return;
  }
  if (targetPath(target) == "/health") {
    sendText(reply, http::status::ok, "application/json", "{\"status\":\"ok\"}\n");
    return;
  }
  if (serveDynamic(reply, target)) return;
  const StaticFile file = resolveStaticFile(transport_.options().staticRoot, target);
  switch (file.lookup) {
    case StaticLookup::BadTarget:
      sendText(reply, http::status::bad_request, "text/plain", "bad request target\n");
      return;
    case StaticLookup::NotFound:
      sendText(reply, http::status::not_found, "text/plain", "not found\n");
      return;
    case StaticLookup::Found:
      sendFile(reply, file.path, contentTypeFor(file.path));
      return;
  }
}

bool HttpSession::serveDynamic(const Reply& reply, std::string_view target) {
  const TransportOptions& options = transport_.options();
  if (!options.httpHandler) return false;
  std::optional<HttpResponse> dynamic;
  try {
    dynamic = options.httpHandler(target);
  } catch (const std::exception& e) {
    sendText(reply, http::status::internal_server_error, "text/plain", std::string("internal error: ") + e.what() + "\n");
    return true;
  }
  if (!dynamic) return false;
  if (!dynamic->file.empty()) {
    sendFile(reply, dynamic->file, dynamic->contentType);
  } else {
    sendText(reply, static_cast<http::status>(dynamic->status), dynamic->contentType, std::move(dynamic->body));
  }
  return true;
}

void HttpSession::handlePost(const Reply& reply, http::request<http::string_body>&& req) {
  auto state = std::make_shared<PostState>();
  state->session = shared_from_this();
  pending_ = state;
  postReply_ = reply;
  stream_.expires_never();  // the answer may take a while (a simulation); a hang-up cancels it
  HttpRequest request;
  request.target.assign(req.target().data(), req.target().size());
  const auto type = req[http::field::content_type];
  request.contentType.assign(type.data(), type.size());
  request.body = std::move(req.body());
  bool taken = false;
  try {
    taken = transport_.options().postHandler(std::move(request), HttpResponder(state));
  } catch (const std::exception& e) {
    state->answer(HttpResponse{500, "text/plain", std::string("internal error: ") + e.what() + "\n", {}});
    return;
  }
  if (!taken) {
    state->answer(HttpResponse{404, "text/plain", "not found\n", {}});
    return;
  }
  if (!state->answered.load()) watchForHangUp();
}

void HttpSession::watchForHangUp() {
  stream_.socket().async_wait(tcp::socket::wait_read, [self = shared_from_this()](error_code ec) {
    if (ec || self->done_) return;  // cancelled by the answer
    auto state = self->pending_.lock();
    if (!state) return;
    error_code availableEc;
    // Readable with nothing to read: the client closed its side. (Bytes waiting are a pipelined
    // request, read after the answer.)
    if (self->stream_.socket().available(availableEc) == 0 || availableEc) {
      state->cancelled.store(1);
      self->finish();
    }
  });
}

void HttpSession::sendPostAnswer(HttpResponse response) {
  pending_.reset();
  if (done_) return;
  error_code ignored;
  stream_.socket().cancel(ignored);  // the hang-up watch
  stream_.expires_after(transport_.options().httpTimeout);
  if (!response.file.empty()) {
    sendFile(postReply_, response.file, response.contentType);
  } else {
    sendText(postReply_, static_cast<http::status>(response.status), response.contentType, std::move(response.body));
  }
}

void HttpSession::sendFile(const Reply& reply, const std::filesystem::path& path, std::string_view contentType) {
  http::file_body::value_type body;
  error_code fileEc;
  body.open(path.c_str(), beast::file_mode::scan, fileEc);
  if (fileEc) {
    send(textResponse(http::status::not_found, "text/plain", "not found\n", reply.version, reply.keepAlive));
    return;
  }
  const auto size = body.size();
  if (reply.head) {
    http::response<http::empty_body> res{http::status::ok, reply.version};
    res.set(http::field::server, "throng");
    res.set(http::field::content_type, beast::string_view(contentType.data(), contentType.size()));
    res.content_length(size);
    res.keep_alive(reply.keepAlive);
    send(std::move(res));
    return;
  }
  http::response<http::file_body> res{std::piecewise_construct, std::make_tuple(std::move(body)),
                                       std::make_tuple(http::status::ok, reply.version)};
  res.set(http::field::server, "throng");
  res.set(http::field::content_type, beast::string_view(contentType.data(), contentType.size()));
  res.content_length(size);
  res.keep_alive(reply.keepAlive);
  send(std::move(res));
}

void HttpSession::sendText(const Reply& reply, http::status status, std::string_view contentType, std::string body) {
  auto res = textResponse(status, contentType, std::move(body), reply.version, reply.keepAlive);
  if (reply.head) {
    const auto length = res.body().size();
    res.body().clear();
    res.content_length(length);
  }
  send(std::move(res));
}

void HttpSession::upgrade(http::request<http::string_body>&& req) {
  if (transport_.stopping() || transport_.peerCount(PeerKind::WebSocket) >= transport_.options().maxPeers) {
    send(textResponse(http::status::service_unavailable, "text/plain",
                      transport_.stopping() ? "server shutting down\n" : "server full\n", req.version(), false));
    return;
  }
  stream_.expires_never();
  const PeerId id = transport_.nextPeerId();
  auto peer = std::make_shared<WsPeer>(transport_, id, std::move(stream_), remote_);
  done_ = true;  // the connection belongs to the peer now
  transport_.removeHttpConnection(registration_);
  if (!transport_.addPeer(peer)) return;  // lost a race for the last slot: the socket closes with the peer
  peer->start(std::move(req));
}

template <class Body>
void HttpSession::send(http::response<Body>&& response) {
  auto res = std::make_shared<http::response<Body>>(std::move(response));
  http::async_write(stream_, *res, [self = shared_from_this(), res](error_code ec, std::size_t) {
    self->onWrite(res->need_eof(), ec);
  });
}

void HttpSession::onWrite(bool close, error_code ec) {
  if (done_) return;
  if (ec || close || transport_.stopping()) {
    finish();
    return;
  }
  doRead();
}

void HttpSession::finish() {
  if (done_) return;
  done_ = true;
  if (auto state = pending_.lock()) state->cancelled.store(1);
  error_code ignored;
  stream_.socket().shutdown(tcp::socket::shutdown_both, ignored);
  stream_.close();
  transport_.removeHttpConnection(registration_);
}

}  // namespace throng::transport::detail
