// Bounded, prioritised fetching of content URLs. The streamer says every so often what it wants
// now (want()): requests no longer wanted are aborted (a camera that moved on, a URL replaced by
// an edit), the rest start highest priority first, at most `concurrency` at a time. A 503 (the
// service's generation queue is full) is retried after its Retry-After; a 404 naming the
// current URL means the index is stale; other failures are reported once and not retried.
export class FetchQueue {
    constructor({ concurrency = 6, load, onLoaded, onFailed, onStale }) {
        this.concurrency = concurrency;
        this.load = load; // (url, signal) => Promise of a value
        this.onLoaded = onLoaded;
        this.onFailed = onFailed;
        this.onStale = onStale;
        this.wanted = new Map(); // url -> request
        this.running = new Map(); // url -> AbortController
        this.failed = new Set();
        this.retryAt = new Map(); // url -> time (ms) before which it is not retried
        this.aborted = 0;
    }

    // `requests`: [{url, priority, ...}] of everything wanted now; higher priority first.
    want(requests) {
        this.wanted = new Map();
        for (const r of requests) if (!this.failed.has(r.url)) this.wanted.set(r.url, r);
        for (const [url, controller] of this.running) {
            if (!this.wanted.has(url)) {
                controller.abort();
                this.running.delete(url);
                ++this.aborted;
            }
        }
        this.pump();
    }

    pump() {
        if (this.running.size >= this.concurrency) return;
        const now = performance.now();
        const queue = [...this.wanted.values()]
            .filter((r) => !this.running.has(r.url) && !((this.retryAt.get(r.url) ?? 0) > now))
            .sort((a, b) => b.priority - a.priority);
        for (const r of queue) {
            if (this.running.size >= this.concurrency) break;
            this.start(r);
        }
    }

    start(r) {
        const controller = new AbortController();
        this.running.set(r.url, controller);
        this.load(r, controller.signal).then(
            (value) => {
                if (this.running.get(r.url) !== controller) return; // aborted meanwhile
                this.running.delete(r.url);
                this.wanted.delete(r.url);
                this.onLoaded(r, value);
                this.pump();
            },
            (error) => {
                if (this.running.get(r.url) !== controller) return;
                this.running.delete(r.url);
                if (error?.name === 'AbortError') return;
                if (error?.status === 503 || error?.status === 429) {
                    const seconds = Number(error.headers?.get?.('Retry-After') ?? 1) || 1;
                    this.retryAt.set(r.url, performance.now() + 1000 * seconds);
                    setTimeout(() => this.pump(), 1000 * seconds + 10);
                } else if (error?.status === 404 && error.headers?.get?.('X-Hexlod-Current')) {
                    this.wanted.delete(r.url);
                    this.onStale(r, error.headers.get('X-Hexlod-Current'));
                } else {
                    this.failed.add(r.url);
                    this.wanted.delete(r.url);
                    this.onFailed(r, error);
                }
                this.pump();
            },
        );
    }

    get pending() {
        return this.wanted.size;
    }
    get inFlight() {
        return this.running.size;
    }
}
