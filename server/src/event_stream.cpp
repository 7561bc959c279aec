#include "event_stream.h"

#include <boost/asio/bind_executor.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>

namespace hexlod::server {

namespace net = boost::asio;

EventStream::EventStream(net::ip::tcp::socket socket, ServerContext& context,
                         std::unique_ptr<OpenConnection> open)
    : socket_(std::move(socket)), context_(context), open_(std::move(open)),
      heartbeat_(socket_.get_executor()), deadline_(socket_.get_executor()) {}

EventStream::~EventStream() {
    context_.connections.remove(registration_);
}

void EventStream::start(std::optional<uint64_t> lastEventId) {
    registration_ = context_.connections.add(weak_from_this());
    boost::system::error_code ignored;
    socket_.set_option(net::socket_base::send_buffer_size(context_.options.eventSendBufferBytes), ignored);
    // No Content-Length and no chunked coding: the body is the stream, ended by closing.
    deliver(std::make_shared<const std::string>("HTTP/1.1 200 OK\r\n"
                                                "Content-Type: text/event-stream; charset=utf-8\r\n"
                                                "Cache-Control: no-store\r\n"
                                                "Connection: keep-alive\r\n"
                                                "X-Accel-Buffering: no\r\n"
                                                "Access-Control-Allow-Origin: *\r\n"
                                                "Server: hexlod\r\n"
                                                "\r\n"
                                                "retry: 2000\n\n"));
    context_.service.events().subscribe(shared_from_this(), lastEventId, jsonText(context_.service.hello()));
    armHeartbeat();
    readUntilClosed();
}

bool EventStream::deliver(EventFrame frame) {
    std::lock_guard lock(mutex_);
    if (closed_) return true; // already on its way out; the hub forgets it on unsubscribe
    if (queue_.size() >= context_.options.eventQueueFrames) return false;
    queue_.push_back(std::move(frame));
    if (!writing_) {
        writing_ = true;
        net::post(socket_.get_executor(), [self = shared_from_this()] { self->writeNext(); });
    }
    return true;
}

void EventStream::writeNext() {
    EventFrame frame;
    {
        std::lock_guard lock(mutex_);
        if (closed_ || queue_.empty()) {
            writing_ = false;
            return;
        }
        frame = queue_.front();
    }
    deadline_.expires_after(context_.options.writeTimeout);
    deadline_.async_wait([self = shared_from_this()](boost::system::error_code ec) {
        if (ec) return;
        self->context_.service.events().drop(self.get()); // the client stopped reading
        self->closeNow();
    });
    net::async_write(socket_, net::buffer(*frame),
                     [self = shared_from_this(), frame](boost::system::error_code ec, size_t) {
                         self->deadline_.cancel();
                         if (ec) return self->closeNow();
                         {
                             std::lock_guard lock(self->mutex_);
                             if (!self->queue_.empty()) self->queue_.pop_front();
                         }
                         self->writeNext();
                     });
}

void EventStream::armHeartbeat() {
    heartbeat_.expires_after(context_.options.heartbeat);
    heartbeat_.async_wait([self = shared_from_this()](boost::system::error_code ec) {
        if (ec) return;
        // Only an idle stream needs a heartbeat: one with frames queued is not idle, and a
        // stalled one is the write deadline's to drop.
        static const EventFrame beat = std::make_shared<const std::string>(EventHub::heartbeatFrame());
        bool idle = false;
        {
            std::lock_guard lock(self->mutex_);
            idle = self->queue_.empty();
        }
        if (idle) self->deliver(beat);
        self->armHeartbeat();
    });
}

void EventStream::readUntilClosed() {
    // A client never sends anything on an event stream; reading only tells us it left.
    socket_.async_read_some(net::buffer(discard_),
                            [self = shared_from_this()](boost::system::error_code ec, size_t) {
                                if (ec) return self->closeNow();
                                self->readUntilClosed();
                            });
}

void EventStream::close() {
    net::post(socket_.get_executor(), [self = shared_from_this()] { self->closeNow(); });
}

void EventStream::closeNow() {
    {
        std::lock_guard lock(mutex_);
        if (closed_) return;
        closed_ = true;
        queue_.clear();
    }
    context_.service.events().unsubscribe(this);
    heartbeat_.cancel();
    deadline_.cancel();
    boost::system::error_code ignored;
    socket_.shutdown(net::ip::tcp::socket::shutdown_both, ignored);
    socket_.close(ignored);
}

} // namespace hexlod::server
