// One HTTP/1.1 connection: reads requests one after another (pipelined ones in order), hands
// each to the API, and writes its reply; keep-alive until the client closes, a limit or a
// timeout is hit, or the server stops. Malformed input gets a 4xx with a reason and closes
// the connection: after a parse error the byte stream cannot be trusted.
#pragma once

#include "server_context.h"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/string_body.hpp>

#include <chrono>
#include <memory>
#include <optional>
#include <string>

namespace hexlod::server {

class HttpSession : public Connection, public std::enable_shared_from_this<HttpSession> {
public:
    HttpSession(boost::asio::ip::tcp::socket socket, ServerContext& context);
    ~HttpSession() override;
    void start();
    void shutdown() override;

private:
    void readHeader();
    void onHeader(boost::beast::error_code ec);
    void readBody();
    void onRequest(boost::beast::error_code ec);
    void readFailed(boost::beast::error_code ec);
    void reply(Reply reply);
    template <class Message> void write(std::shared_ptr<Message> message, bool keepAlive);
    void onWrite(boost::beast::error_code ec, bool keepAlive);
    void lingerClose();
    void becomeEventStream(const Reply& reply);
    void closeNow();

    boost::beast::tcp_stream stream_;
    // The request deadline is a timer of our own: the stream's timeout closes the socket,
    // which would leave no way to answer 408.
    boost::asio::steady_timer deadline_;
    bool timedOut_ = false;
    ServerContext& context_;
    std::unique_ptr<OpenConnection> open_;
    boost::beast::flat_buffer buffer_;
    std::optional<boost::beast::http::request_parser<boost::beast::http::string_body>> parser_;
    std::shared_ptr<void> writing_; // the message being written, kept alive until done
    PayloadBytes payload_;          // bytes a span body points into
    std::string remote_;
    uint64_t registration_ = 0;

    // The request being answered.
    std::string route_;
    int status_ = 0;
    uint64_t bodyBytes_ = 0;
    bool keepAlive_ = true;
    bool head_ = false;
    bool busy_ = false;    // between a complete request and its written reply
    bool closing_ = false; // a graceful stop asked to close after the current reply
    std::chrono::steady_clock::time_point received_;
};

} // namespace hexlod::server
