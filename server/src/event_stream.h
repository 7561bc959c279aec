// One Server-Sent Events client (https://html.spec.whatwg.org/multipage/server-sent-events.html):
// after the response header, frames from the EventHub are queued and written one at a time
// on the connection's strand; a heartbeat comment keeps proxies from closing an idle stream.
// A client whose queue overflows or whose write stalls past the write timeout is dropped.
#pragma once

#include "server_context.h"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>

#include <array>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>

namespace hexlod::server {

class EventStream : public EventSubscriber,
                    public Connection,
                    public std::enable_shared_from_this<EventStream> {
public:
    EventStream(boost::asio::ip::tcp::socket socket, ServerContext& context,
                std::unique_ptr<OpenConnection> open);
    ~EventStream() override;

    void start(std::optional<uint64_t> lastEventId);
    bool deliver(EventFrame frame) override;
    void close() override;
    void shutdown() override { close(); }

private:
    void writeNext();
    void armHeartbeat();
    void readUntilClosed();
    void closeNow();

    boost::asio::ip::tcp::socket socket_;
    ServerContext& context_;
    std::unique_ptr<OpenConnection> open_;
    boost::asio::steady_timer heartbeat_, deadline_;
    std::array<char, 512> discard_{};
    std::mutex mutex_; // guards the queue and the flags; deliver() runs on edit threads
    std::deque<EventFrame> queue_;
    bool writing_ = false;
    bool closed_ = false;
    uint64_t registration_ = 0;
};

} // namespace hexlod::server
