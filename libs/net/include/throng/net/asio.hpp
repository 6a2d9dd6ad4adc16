// throng::net — the Boost.Asio / Beast headers and the short names both network sides are written
// with: the server transport (libs/transport) and the client sockets (libs/client). Header only;
// their sources say `using namespace throng::net;` inside a private namespace. No I/O of its own.
#pragma once
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

namespace throng::net {
namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = boost::beast::http;
namespace websocket = boost::beast::websocket;
using tcp = boost::asio::ip::tcp;
using udp = boost::asio::ip::udp;
using error_code = boost::system::error_code;
}  // namespace throng::net
