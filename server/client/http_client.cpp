#include "hexlod/http_client/http_client.h"

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/http/write.hpp>

#include <cctype>
#include <stdexcept>
#include <sys/socket.h>
#include <sys/time.h>

namespace hexlod::http_client {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;

namespace {

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

void setReceiveTimeout(tcp::socket& socket, std::chrono::milliseconds timeout) {
    const auto ms = std::max<int64_t>(1, timeout.count());
    timeval tv{static_cast<time_t>(ms / 1000), static_cast<suseconds_t>((ms % 1000) * 1000)};
    ::setsockopt(socket.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
    ::setsockopt(socket.native_handle(), SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof(tv));
}

void connectTo(net::io_context& ioc, tcp::socket& socket, const std::string& host, uint16_t port) {
    tcp::resolver resolver(ioc);
    net::connect(socket, resolver.resolve(host, std::to_string(port)));
}

} // namespace

std::string Response::header(const std::string& lowerName) const {
    const auto it = headers.find(lowerName);
    return it == headers.end() ? std::string() : it->second;
}

struct Connection::Impl {
    net::io_context ioc;
    tcp::socket socket{ioc};
    beast::flat_buffer buffer;
    bool open = false;
    bool lastWasHead = false;
};

Connection::Connection(const std::string& host, uint16_t port, std::chrono::milliseconds timeout)
    : impl_(std::make_unique<Impl>()), host_(host + ":" + std::to_string(port)) {
    connectTo(impl_->ioc, impl_->socket, host, port);
    setReceiveTimeout(impl_->socket, timeout);
    impl_->open = true;
}

Connection::~Connection() {
    beast::error_code ignored;
    impl_->socket.shutdown(tcp::socket::shutdown_both, ignored);
    impl_->socket.close(ignored);
}

bool Connection::isOpen() const {
    return impl_->open;
}

Response Connection::request(const std::string& method, const std::string& target, const std::string& body,
                             const Headers& headers) {
    http::request<http::string_body> req;
    req.method_string(method);
    req.target(target);
    req.version(11);
    req.set(http::field::host, host_);
    req.set(http::field::user_agent, "hexlod-test-client");
    for (const auto& [name, value] : headers) req.set(name, value);
    req.body() = body;
    if (!body.empty() || method == "POST" || method == "PUT") req.prepare_payload();
    beast::error_code ec;
    http::write(impl_->socket, req, ec);
    if (ec) {
        impl_->open = false;
        return {};
    }
    impl_->lastWasHead = method == "HEAD";
    return readResponse();
}

Response Connection::post(const std::string& target, const std::string& body, const Headers& headers) {
    Headers all = headers;
    bool typed = false;
    for (const auto& [name, value] : headers) typed = typed || lower(name) == "content-type";
    if (!typed) all.emplace_back("Content-Type", "application/json");
    return request("POST", target, body, all);
}

Response Connection::raw(std::string_view bytes) {
    beast::error_code ec;
    net::write(impl_->socket, net::buffer(bytes.data(), bytes.size()), ec);
    impl_->lastWasHead = bytes.substr(0, 5) == "HEAD ";
    if (ec) {
        impl_->open = false;
        return {};
    }
    return readResponse();
}

Response Connection::readResponse() {
    http::response_parser<http::string_body> parser;
    parser.body_limit(uint64_t(1) << 32);
    parser.skip(impl_->lastWasHead);
    beast::error_code ec;
    http::read(impl_->socket, impl_->buffer, parser, ec);
    if (ec) {
        impl_->open = false;
        return {};
    }
    const auto& message = parser.get();
    Response response;
    response.status = static_cast<int>(message.result_int());
    for (const auto& field : message)
        response.headers[lower(std::string_view(field.name_string().data(), field.name_string().size()))] =
            std::string(field.value());
    response.body = message.body();
    if (!message.keep_alive()) impl_->open = false;
    return response;
}

Response fetch(const std::string& host, uint16_t port, const std::string& method, const std::string& target,
               const std::string& body, const Headers& headers) {
    Connection connection(host, port);
    return connection.request(method, target, body, headers);
}

struct EventStreamReader::Impl {
    net::io_context ioc;
    tcp::socket socket{ioc};
    bool closed = false;
};

EventStreamReader::EventStreamReader(const std::string& host, uint16_t port, const std::string& target,
                                     const Headers& headers, int receiveBufferBytes)
    : impl_(std::make_unique<Impl>()) {
    if (receiveBufferBytes > 0) {
        tcp::resolver resolver(impl_->ioc);
        const auto endpoints = resolver.resolve(host, std::to_string(port));
        impl_->socket.open(endpoints.begin()->endpoint().protocol());
        impl_->socket.set_option(net::socket_base::receive_buffer_size(receiveBufferBytes));
        impl_->socket.connect(*endpoints.begin());
    } else {
        connectTo(impl_->ioc, impl_->socket, host, port);
    }
    std::string request = "GET " + target + " HTTP/1.1\r\nHost: " + host + ":" + std::to_string(port) +
                          "\r\nAccept: text/event-stream\r\n";
    for (const auto& [name, value] : headers) request += name + ": " + value + "\r\n";
    request += "\r\n";
    net::write(impl_->socket, net::buffer(request));
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    size_t end = std::string::npos;
    while ((end = buffer_.find("\r\n\r\n")) == std::string::npos)
        if (!readMore(deadline)) return;
    const std::string head = buffer_.substr(0, end);
    buffer_.erase(0, end + 4);
    const size_t space = head.find(' ');
    if (space != std::string::npos) status_ = std::atoi(head.c_str() + space + 1);
    for (size_t at = head.find("\r\n"); at != std::string::npos;) {
        const size_t next = head.find("\r\n", at + 2);
        const std::string line =
            head.substr(at + 2, next == std::string::npos ? std::string::npos : next - at - 2);
        const size_t colon = line.find(':');
        if (colon != std::string::npos) {
            size_t value = colon + 1;
            while (value < line.size() && line[value] == ' ') ++value;
            headers_[lower(line.substr(0, colon))] = line.substr(value);
        }
        at = next;
    }
}

EventStreamReader::~EventStreamReader() {
    beast::error_code ignored;
    impl_->socket.close(ignored);
}

std::string EventStreamReader::header(const std::string& lowerName) const {
    const auto it = headers_.find(lowerName);
    return it == headers_.end() ? std::string() : it->second;
}

void EventStreamReader::close() {
    impl_->closed = true;
}

bool EventStreamReader::readMore(std::chrono::steady_clock::time_point deadline) {
    if (impl_->closed) return false;
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    setReceiveTimeout(impl_->socket, left);
    char chunk[8192];
    beast::error_code ec;
    const size_t n = impl_->socket.read_some(net::buffer(chunk), ec);
    if (ec) return false;
    buffer_.append(chunk, n);
    return true;
}

std::optional<ServerSentEvent> EventStreamReader::next(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (true) {
        const size_t end = buffer_.find("\n\n");
        if (end == std::string::npos) {
            if (!readMore(deadline)) return std::nullopt;
            continue;
        }
        const std::string frame = buffer_.substr(0, end);
        buffer_.erase(0, end + 2);
        ServerSentEvent event;
        bool any = false;
        for (size_t at = 0; at <= frame.size();) {
            size_t nl = frame.find('\n', at);
            if (nl == std::string::npos) nl = frame.size();
            const std::string line = frame.substr(at, nl - at);
            at = nl + 1;
            if (line.empty() || line[0] == ':') continue;
            const size_t colon = line.find(':');
            const std::string field = line.substr(0, colon);
            std::string value = colon == std::string::npos ? "" : line.substr(colon + 1);
            if (!value.empty() && value[0] == ' ') value.erase(0, 1);
            if (field == "id") event.id = value, any = true;
            if (field == "event") event.event = value, any = true;
            if (field == "data") event.data += (event.data.empty() ? "" : "\n") + value, any = true;
        }
        if (any && !event.event.empty()) return event;
        if (any && !event.data.empty()) return event;
    }
}

} // namespace hexlod::http_client
