#include "http_session.h"

#include "event_stream.h"

#include "hexlod/server/beast_request.h"

#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core/bind_handler.hpp>
#include <boost/beast/core/span.hpp>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/file_body.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/span_body.hpp>
#include <boost/beast/http/write.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace hexlod::server {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;

namespace {

bool isHttpError(const beast::error_code& ec) {
    return ec.category() == http::make_error_code(http::error::bad_method).category();
}

std::string lowerCase(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::string seconds(std::chrono::milliseconds ms) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f", static_cast<double>(ms.count()) / 1000.0);
    return text;
}

} // namespace

HttpSession::HttpSession(net::ip::tcp::socket socket, ServerContext& context)
    : stream_(std::move(socket)), deadline_(stream_.get_executor()), context_(context),
      open_(std::make_unique<OpenConnection>(context.service.metrics())),
      buffer_(context.options.maxHeaderBytes + context.options.maxBodyBytes + 4096) {
    beast::error_code ec;
    const auto endpoint = stream_.socket().remote_endpoint(ec);
    remote_ = ec ? "unknown" : endpoint.address().to_string();
}

HttpSession::~HttpSession() {
    context_.connections.remove(registration_);
}

void HttpSession::start() {
    ++context_.service.metrics().connectionsOpened;
    registration_ = context_.connections.add(weak_from_this());
    net::dispatch(stream_.get_executor(), [self = shared_from_this()] { self->readHeader(); });
}

void HttpSession::shutdown() {
    net::post(stream_.get_executor(), [self = shared_from_this()] {
        self->closing_ = true;
        if (!self->busy_) self->stream_.cancel(); // an idle keep-alive read ends now
    });
}

void HttpSession::readHeader() {
    if (closing_ || context_.stopping) return closeNow();
    parser_.emplace();
    parser_->header_limit(static_cast<std::uint32_t>(context_.options.maxHeaderBytes));
    parser_->body_limit(context_.options.maxBodyBytes);
    // One deadline for idle time, header and body: a slow client cannot hold the connection
    // longer than requestTimeout per request, however it spaces its bytes.
    stream_.expires_never();
    timedOut_ = false;
    deadline_.expires_after(context_.options.requestTimeout);
    deadline_.async_wait([self = shared_from_this()](beast::error_code ec) {
        if (ec) return; // re-armed or cancelled: the request arrived
        self->timedOut_ = true;
        beast::error_code ignored;
        self->stream_.socket().cancel(ignored); // the read ends with operation_aborted
    });
    http::async_read_header(
        stream_, buffer_, *parser_,
        [self = shared_from_this()](beast::error_code ec, size_t) { self->onHeader(ec); });
}

void HttpSession::onHeader(beast::error_code ec) {
    if (ec) return readFailed(ec);
    const auto& message = parser_->get();
    const auto expect = message.find(http::field::expect);
    if (expect != message.end() &&
        lowerCase(std::string_view(expect->value().data(), expect->value().size())) == "100-continue" &&
        !parser_->is_done()) {
        static const std::string kContinue = "HTTP/1.1 100 Continue\r\n\r\n";
        net::async_write(stream_, net::buffer(kContinue),
                         [self = shared_from_this()](beast::error_code ec, size_t) {
                             if (ec) return self->closeNow();
                             self->readBody();
                         });
        return;
    }
    readBody();
}

void HttpSession::readBody() {
    http::async_read(stream_, buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code ec, size_t) { self->onRequest(ec); });
}

void HttpSession::readFailed(beast::error_code ec) {
    deadline_.cancel();
    if (timedOut_ && ec == net::error::operation_aborted) {
        if (parser_ && parser_->got_some()) {
            route_ = "malformed";
            busy_ = true;
            keepAlive_ = false;
            received_ = std::chrono::steady_clock::now();
            Reply r = errorReply(408, "the request did not arrive within " +
                                          seconds(context_.options.requestTimeout) + " s");
            r.closeConnection = true;
            return reply(std::move(r));
        }
        return closeNow();
    }
    if (!isHttpError(ec) || ec == http::error::end_of_stream) return closeNow();
    ++context_.service.metrics().malformed;
    int status = 400;
    std::string reason = "malformed request: " + ec.message();
    if (ec == http::error::header_limit || ec == http::error::buffer_overflow) {
        status = 431;
        reason = "request header larger than " + std::to_string(context_.options.maxHeaderBytes) + " bytes";
    } else if (ec == http::error::body_limit) {
        status = 413;
        reason = "request body larger than " + std::to_string(context_.options.maxBodyBytes) + " bytes";
    } else if (ec == http::error::bad_version) {
        status = 505;
        reason = "only HTTP/1.0 and HTTP/1.1 are spoken here";
    } else if (ec == http::error::partial_message) {
        return closeNow(); // the client left mid-request: nobody to answer
    }
    route_ = "malformed";
    busy_ = true;
    keepAlive_ = false;
    head_ = false;
    received_ = std::chrono::steady_clock::now();
    Reply r = errorReply(status, reason);
    r.closeConnection = true;
    reply(std::move(r));
}

void HttpSession::onRequest(beast::error_code ec) {
    if (ec) return readFailed(ec);
    deadline_.cancel(); // the handler may take a while (generation); writes set their own
    received_ = std::chrono::steady_clock::now();
    busy_ = true;
    auto& message = parser_->get();
    keepAlive_ = message.keep_alive();
    head_ = message.method() == http::verb::head;
    const auto early = [&](Reply r, const char* route) {
        route_ = route;
        reply(std::move(r));
    };
    if (std::optional<Reply> rejected = rejectBeforeRouting(message))
        return early(std::move(*rejected), "malformed");
    if (const uint32_t wait = context_.limiter.acquire(remote_)) {
        ++context_.service.metrics().rateLimited;
        Reply r = errorReply(429, "too many requests from " + remote_ + "; retry in " + std::to_string(wait) +
                                      " s");
        r.set("Retry-After", std::to_string(wait));
        return early(std::move(r), "rate_limited");
    }
    Request request = toRequest(std::move(message), remote_);
    parser_.reset();
    auto self = shared_from_this();
    const Respond respond = [self](Reply r) {
        net::post(self->stream_.get_executor(),
                  [self, r = std::move(r)]() mutable { self->reply(std::move(r)); });
    };
    try {
        route_ = context_.api.handle(request, respond);
    } catch (const std::exception& e) {
        // A handler bug must cost one request, not the process: io_context::run would rethrow it.
        route_ = "failed";
        respond(errorReply(500, std::string("internal error: ") + e.what()));
    }
}

void HttpSession::reply(Reply r) {
    status_ = r.status;
    bodyBytes_ = head_ ? 0 : r.bodyBytes();
    if (r.eventStream && !head_) return becomeEventStream(r);
    const bool keepAlive = keepAlive_ && !r.closeConnection && !closing_ && !context_.stopping;
    const auto fill = [&](auto& m) {
        m.version(11);
        m.result(static_cast<unsigned>(r.status));
        m.set(http::field::server, "hexlod");
        m.set("X-Content-Type-Options", "nosniff");
        if (!r.contentType.empty()) m.set(http::field::content_type, r.contentType);
        for (const auto& [name, value] : r.headers) m.set(name, value);
        m.keep_alive(keepAlive);
    };
    if (r.status == 304 || r.status == 204 || head_ || r.eventStream) {
        auto m = std::make_shared<http::response<http::empty_body>>();
        fill(*m);
        if (head_ && r.status != 304 && r.status != 204) m->content_length(r.eventStream ? 0 : r.bodyBytes());
        return write(std::move(m), keepAlive);
    }
    if (r.payload) {
        payload_ = r.payload;
        auto m = std::make_shared<http::response<http::span_body<const char>>>();
        fill(*m);
        m->body() =
            beast::span<const char>(reinterpret_cast<const char*>(payload_->data()), payload_->size());
        m->prepare_payload();
        return write(std::move(m), keepAlive);
    }
    if (!r.filePath.empty()) {
        auto m = std::make_shared<http::response<http::file_body>>();
        fill(*m);
        beast::error_code ec;
        m->body().open(r.filePath.c_str(), beast::file_mode::scan, ec);
        if (ec) return reply(errorReply(404, "no such file"));
        m->prepare_payload();
        bodyBytes_ = m->body().size();
        return write(std::move(m), keepAlive);
    }
    auto m = std::make_shared<http::response<http::string_body>>();
    fill(*m);
    m->body() = std::move(r.body);
    m->prepare_payload();
    write(std::move(m), keepAlive);
}

template <class Message> void HttpSession::write(std::shared_ptr<Message> message, bool keepAlive) {
    writing_ = message;
    stream_.expires_after(context_.options.writeTimeout);
    http::async_write(stream_, *message,
                      [self = shared_from_this(), keepAlive](beast::error_code ec, size_t) {
                          self->onWrite(ec, keepAlive);
                      });
}

void HttpSession::onWrite(beast::error_code ec, bool keepAlive) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - received_).count();
    context_.service.metrics().recordRequest(route_, status_, elapsed, ec ? 0 : bodyBytes_);
    writing_.reset();
    payload_.reset();
    busy_ = false;
    if (ec) return closeNow();
    if (!keepAlive || closing_ || context_.stopping) {
        // Lingering close: stop sending, then read what the client still sends (pipelined
        // bytes after an error) until it closes, so that our reply is not lost to a reset.
        beast::error_code ignored;
        stream_.socket().shutdown(net::ip::tcp::socket::shutdown_send, ignored);
        stream_.expires_after(std::chrono::seconds(1));
        return lingerClose();
    }
    readHeader();
}

void HttpSession::lingerClose() {
    buffer_.consume(buffer_.size());
    stream_.async_read_some(buffer_.prepare(4096), [self = shared_from_this()](beast::error_code ec, size_t) {
        if (ec) return self->closeNow();
        self->lingerClose();
    });
}

void HttpSession::becomeEventStream(const Reply& r) {
    context_.service.metrics().recordRequest(route_, 200, 0.0, 0);
    stream_.expires_never();
    context_.connections.remove(registration_);
    registration_ = 0;
    auto events = std::make_shared<EventStream>(stream_.release_socket(), context_, std::move(open_));
    events->start(r.lastEventId);
}

void HttpSession::closeNow() {
    deadline_.cancel();
    beast::error_code ignored;
    stream_.socket().shutdown(net::ip::tcp::socket::shutdown_both, ignored);
    stream_.socket().close(ignored);
}

} // namespace hexlod::server
