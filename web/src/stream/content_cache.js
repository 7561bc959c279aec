// The viewer's LRU of decoded cell content (terminal and extruded sets with their GPU objects),
// bounded by a byte budget: decoded records plus the GPU buffers built from them. Content in
// use by the current frame is pinned and never evicted; beyond the budget the least recently
// used unpinned entries are disposed, so memory stays bounded however far the camera walks.
export class ContentCache {
    constructor(budgetBytes, onEvict) {
        this.budget = budgetBytes;
        this.onEvict = onEvict;
        this.entries = new Map(); // url -> {url, bytes, value, used}; Map order is insertion order
        this.bytes = 0;
        this.evictions = 0;
    }

    get(url) {
        const entry = this.entries.get(url);
        if (!entry) return undefined;
        this.entries.delete(url);
        this.entries.set(url, entry); // most recently used last
        return entry.value;
    }

    has(url) {
        return this.entries.has(url);
    }

    // The bytes an entry counts now, 0 for none (url null or not cached); it is not touched.
    bytesOf(url) {
        return this.entries.get(url)?.bytes ?? 0;
    }

    // Every entry, {url, value, bytes}, least recently used first; none is touched.
    list() {
        return this.entries.values();
    }

    put(url, value, bytes) {
        this.remove(url);
        this.entries.set(url, { url, value, bytes });
        this.bytes += bytes;
    }

    // Content grows when its GPU objects are built.
    grow(url, bytes) {
        const entry = this.entries.get(url);
        if (!entry) return;
        entry.bytes += bytes;
        this.bytes += bytes;
    }

    remove(url) {
        const entry = this.entries.get(url);
        if (!entry) return;
        this.entries.delete(url);
        this.bytes -= entry.bytes;
        this.onEvict?.(entry.value, url);
    }

    // Evicts least recently used entries not in `pinned` (a Set of urls) until within budget.
    trim(pinned) {
        for (const [url] of this.entries) {
            if (this.bytes <= this.budget) break;
            if (pinned.has(url)) continue;
            this.remove(url);
            ++this.evictions;
        }
    }

    get size() {
        return this.entries.size;
    }
}
