// Change events for Server-Sent Events subscribers (docs/protocol.md, "GET /api/v1/events").
// publish() formats one frame and hands it to every subscriber without waiting for any: a
// subscriber queues it and writes it on its own time, and one whose queue overflows is
// dropped, so a slow client never holds up an edit. The last frames are retained so that a
// client reconnecting with Last-Event-ID gets what it missed, or a "reset" event when those
// frames are gone.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace hexlod::server {

using EventFrame = std::shared_ptr<const std::string>;

class EventSubscriber {
public:
    virtual ~EventSubscriber() = default;
    // Must not block. False when the subscriber cannot take the frame (its queue is full): the
    // hub then drops it and calls close().
    virtual bool deliver(EventFrame frame) = 0;
    virtual void close() = 0;
};

struct EventHubStats {
    uint64_t published = 0, delivered = 0, dropped = 0;
    uint32_t subscribers = 0;
};

class EventHub {
public:
    explicit EventHub(size_t retainedFrames = 1024) : retained_(retainedFrames) {}

    // Ids are edit sequence numbers; the first event after `seq` will be seq + 1.
    void setBaseline(uint64_t seq);
    void publish(uint64_t id, const std::string& event, const std::string& json);
    // An event without id, not retained: a notice that is not an edit, whose state a
    // reconnecting client reads from the hello and the API instead.
    void notify(const std::string& event, const std::string& json);
    // Sends `hello` (an event without id) first, then, with lastEventId, the retained frames
    // after it, or a "reset" event when some of them are no longer retained.
    void subscribe(const std::shared_ptr<EventSubscriber>& subscriber, std::optional<uint64_t> lastEventId,
                   const std::string& helloJson);
    void unsubscribe(const EventSubscriber* subscriber);
    // Unsubscribes a subscriber that gave up on its own (its writes stalled) and counts it as dropped.
    void drop(const EventSubscriber* subscriber);
    void closeAll();
    EventHubStats stats() const;

    static std::string formatFrame(std::optional<uint64_t> id, const std::string& event,
                                   const std::string& json);
    static std::string heartbeatFrame(); // a comment line, ignored by EventSource

private:
    // Retains the frame when it has an id, hands it to every subscriber, and closes those
    // that overflowed once the lock is released.
    void send(std::optional<uint64_t> id, const std::string& event, const std::string& json);

    const size_t retained_;
    mutable std::mutex mutex_;
    std::vector<std::shared_ptr<EventSubscriber>> subscribers_;
    std::deque<std::pair<uint64_t, EventFrame>> recent_;
    uint64_t lastId_ = 0;
    EventHubStats stats_;
};

} // namespace hexlod::server
