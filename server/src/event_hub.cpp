#include "hexlod/server/event_hub.h"

#include <algorithm>

namespace hexlod::server {

std::string EventHub::formatFrame(std::optional<uint64_t> id, const std::string& event,
                                  const std::string& json) {
    std::string frame;
    if (id) frame += "id: " + std::to_string(*id) + "\n";
    frame += "event: " + event + "\n";
    // JSON from nlohmann's dump() holds no raw newline; one data line is enough.
    frame += "data: " + json + "\n\n";
    return frame;
}

std::string EventHub::heartbeatFrame() {
    return ": heartbeat\n\n";
}

void EventHub::setBaseline(uint64_t seq) {
    std::lock_guard lock(mutex_);
    lastId_ = seq;
}

void EventHub::publish(uint64_t id, const std::string& event, const std::string& json) {
    send(id, event, json);
}

void EventHub::notify(const std::string& event, const std::string& json) {
    send(std::nullopt, event, json);
}

void EventHub::send(std::optional<uint64_t> id, const std::string& event, const std::string& json) {
    const EventFrame frame = std::make_shared<const std::string>(formatFrame(id, event, json));
    std::vector<std::shared_ptr<EventSubscriber>> overflowed;
    {
        std::lock_guard lock(mutex_);
        ++stats_.published;
        if (id) {
            lastId_ = *id;
            recent_.emplace_back(*id, frame);
            while (recent_.size() > retained_) recent_.pop_front();
        }
        for (auto it = subscribers_.begin(); it != subscribers_.end();) {
            if ((*it)->deliver(frame)) {
                ++stats_.delivered;
                ++it;
            } else {
                ++stats_.dropped;
                overflowed.push_back(std::move(*it));
                it = subscribers_.erase(it);
            }
        }
    }
    for (const auto& subscriber : overflowed) subscriber->close();
}

void EventHub::subscribe(const std::shared_ptr<EventSubscriber>& subscriber,
                         std::optional<uint64_t> lastEventId, const std::string& helloJson) {
    std::lock_guard lock(mutex_);
    subscriber->deliver(std::make_shared<const std::string>(formatFrame(std::nullopt, "hello", helloJson)));
    if (lastEventId && *lastEventId < lastId_) {
        const bool complete = !recent_.empty() && recent_.front().first <= *lastEventId + 1;
        if (complete) {
            for (const auto& [id, frame] : recent_)
                if (id > *lastEventId) subscriber->deliver(frame);
        } else {
            subscriber->deliver(std::make_shared<const std::string>(
                formatFrame(std::nullopt, "reset",
                            "{\"reason\":\"events after " + std::to_string(*lastEventId) +
                                " are no longer retained: fetch /api/v1/cells again\"}")));
        }
    }
    subscribers_.push_back(subscriber);
}

void EventHub::unsubscribe(const EventSubscriber* subscriber) {
    std::lock_guard lock(mutex_);
    std::erase_if(subscribers_, [&](const auto& s) { return s.get() == subscriber; });
}

void EventHub::drop(const EventSubscriber* subscriber) {
    std::lock_guard lock(mutex_);
    const size_t before = subscribers_.size();
    std::erase_if(subscribers_, [&](const auto& s) { return s.get() == subscriber; });
    stats_.dropped += before - subscribers_.size();
}

void EventHub::closeAll() {
    std::vector<std::shared_ptr<EventSubscriber>> all;
    {
        std::lock_guard lock(mutex_);
        all.swap(subscribers_);
    }
    for (const auto& subscriber : all) subscriber->close();
}

EventHubStats EventHub::stats() const {
    std::lock_guard lock(mutex_);
    EventHubStats s = stats_;
    s.subscribers = static_cast<uint32_t>(subscribers_.size());
    return s;
}

} // namespace hexlod::server
