// Edit-in-place tuning over the API: POST /api/v1/edits (a selector and parameter values),
// POST /api/v1/edits/undo, and the change events of /api/v1/events (Server-Sent Events). An
// edit reply and its event carry the same `changed` list (new key, version and URLs per
// batch); whichever comes first is applied and the other is a no-op, since a batch only ever
// moves to a higher version. A `reset` event, or a `hello` whose seq differs from the index's,
// means events were missed: the cell index is fetched again. A `species` event (no id, not
// replayed) announces a tree species the service baked for edited trees; the hello's species
// count tells a reconnecting client whether it missed one.
import { postJson } from '../api.js';

export class EditClient {
    constructor({ onChanged, onReset, onStatus, onSpecies, onSpeciesCount }) {
        this.onChanged = onChanged;
        this.onReset = onReset;
        this.onStatus = onStatus;
        this.onSpecies = onSpecies;
        this.onSpeciesCount = onSpeciesCount;
        this.indexSeq = 0;
        this.lastEvent = null;
        this.posting = 0; // edits and undos in flight
        this.postingSince = null; // when the latest of them was posted; null: none in flight
        this.lastPost = null;
    }

    connect() {
        this.source = new EventSource('/api/v1/events');
        this.source.addEventListener('hello', (e) => {
            const hello = JSON.parse(e.data);
            this.onStatus('events: connected');
            if (hello.seq !== this.indexSeq) this.onReset();
            if (hello.tree_species !== undefined) this.onSpeciesCount?.(hello.tree_species);
        });
        this.source.addEventListener('species', (e) => this.onSpecies?.(JSON.parse(e.data).species));
        for (const type of ['edit', 'undo']) {
            this.source.addEventListener(type, (e) => {
                const event = JSON.parse(e.data);
                this.lastEvent = { type, seq: event.seq, at: performance.now() };
                this.indexSeq = Math.max(this.indexSeq, event.seq);
                this.onChanged(event.changed, event);
            });
        }
        this.source.addEventListener('reset', () => this.onReset());
        this.source.onerror = () => this.onStatus('events: reconnecting');
    }

    // `selector`: {buildings: [id]} | {cell: [q, r]} | {grammar: name or index}. Throws ApiError
    // (with the service's reason and field) when the edit is refused.
    async edit(selector, params, comment) {
        const body = { selector, params };
        if (comment) body.comment = comment;
        return this.post('/api/v1/edits', body);
    }

    async undo() {
        return this.post('/api/v1/edits/undo', {});
    }

    // `lastPost` times this client's own latest edit or undo: when it was posted and when its
    // reply came; the viewer adds when its changed batches were first drawn (shownAt), which
    // is what a user tuning a parameter waits for.
    async post(url, body) {
        const postedAt = performance.now();
        this.postingSince = postedAt;
        ++this.posting;
        let reply;
        try {
            reply = await postJson(url, body);
        } finally {
            if (--this.posting === 0) this.postingSince = null;
        }
        // Replies to overlapping posts may come in any order: the latest edit is the one timed.
        if (!this.lastPost || reply.seq > this.lastPost.seq)
            this.lastPost = { seq: reply.seq, postedAt, repliedAt: performance.now(), changed: reply.changed ?? [], shownAt: null };
        this.indexSeq = Math.max(this.indexSeq, reply.seq);
        this.onChanged(reply.changed, reply);
        return reply;
    }
}
