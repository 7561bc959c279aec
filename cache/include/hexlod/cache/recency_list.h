// Keys from the most to the least recently used, with the superseded ones (versions nothing
// current has any more: a batch's keys from before an edit) apart at the cold end. Eviction
// from the cold end then takes them first, those superseded longest ago first, and current
// content only once they are gone: a tuning session's old versions cannot push the city out.
#pragma once

#include <iterator>
#include <list>

namespace hexlod::cache {

template <typename Key> class RecencyList {
    struct Node {
        Key key;
        bool superseded = false;
    };

public:
    using Position = typename std::list<Node>::iterator;

    RecencyList() = default;
    RecencyList(const RecencyList&) = delete; // the marker points into this list
    RecencyList& operator=(const RecencyList&) = delete;

    // Hottest first: current entries by recency, then the superseded ones, most recently
    // superseded first.
    Position begin() { return nodes_.begin(); }
    Position end() { return nodes_.end(); }
    Position coldest() { return std::prev(nodes_.end()); }

    Position pushFront(const Key& key) {
        nodes_.push_front({key, false});
        return nodes_.begin();
    }
    // Most recently used, and current again if it was superseded.
    void touch(Position p) {
        unmark(p);
        nodes_.splice(nodes_.begin(), nodes_, p);
    }
    // To the head of the superseded entries: an undo most likely wants the latest ones.
    void supersede(Position p) {
        if (p->superseded) return;
        nodes_.splice(firstSuperseded_, nodes_, p);
        p->superseded = true;
        firstSuperseded_ = p;
    }
    Position erase(Position p) {
        unmark(p);
        return nodes_.erase(p);
    }

private:
    void unmark(Position p) {
        if (!p->superseded) return;
        if (p == firstSuperseded_) ++firstSuperseded_;
        p->superseded = false;
    }

    std::list<Node> nodes_;
    Position firstSuperseded_ = nodes_.end(); // end(): none
};

} // namespace hexlod::cache
