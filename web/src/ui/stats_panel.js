// The stats overlay: frame rate, cells per LOD (and far batches drawn as points), terminals drawn
// per LOD, tree billboards, bytes downloaded, the content cache, pending requests, where meshes,
// impostors and tree impostors come from (or why not), how long the latest edit took to show, and
// the versions of the batches drawn (edited ones, and the selected cell's).
const MiB = 1024 * 1024;

// How long the user's latest edit took, the POST's reply and then its changed batches on
// screen: appended to the versions line, so the panel does not grow over the view.
function lastEdit(post) {
    if (!post) return '';
    const reply = ((post.repliedAt - post.postedAt) / 1000).toFixed(2);
    if (post.shownAt === null) return `   last edit ${post.seq}: reply in ${reply} s, waiting for its content`;
    if (!post.inView) return `   last edit ${post.seq}: reply in ${reply} s, none of its batches in view`;
    return `   last edit ${post.seq}: reply in ${reply} s, on screen ${((post.shownAt - post.postedAt) / 1000).toFixed(2)} s after its POST`;
}

export class StatsPanel {
    constructor(element) {
        this.element = element;
        this.frames = [];
    }

    frame(now) {
        this.frames.push(now);
        while (this.frames.length > 1 && now - this.frames[0] > 1000) this.frames.shift();
    }

    get fps() {
        if (this.frames.length < 2) return 0;
        return ((this.frames.length - 1) * 1000) / (this.frames[this.frames.length - 1] - this.frames[0]);
    }

    show(s) {
        const lines = [
            `fps ${this.fps.toFixed(1)}   mode ${s.mode}   speed ${s.speed.toFixed(1)} m/s   ${s.events}`,
            `camera ${s.position.map((v) => v.toFixed(1)).join(', ')}`,
            `cells in view ${s.streamer.visible}: LOD0 (extruded) ${s.streamer.cells.extruded}, terminal sets ${s.streamer.cells.terminals}${s.streamer.cells.held ? ` (${s.streamer.cells.held} held back by the cache budget: LOD0, trees as billboards)` : ''}${s.streamer.pointBatches ? `; ${s.streamer.pointBatches} far batches as points` : ''}`,
            `terminals drawn: LOD4 ${s.streamer.terminals[4]} (coarse mesh ${s.streamer.terminals.coarse}), LOD3 ${s.streamer.terminals[3]}, LOD2 ${s.streamer.terminals[2]}; ${s.occlusion}`,
            `trees: ${s.streamer.trees.billboards} billboards${s.streamer.trees.occluded ? ` (${s.streamer.trees.occluded} of them hidden)` : ''}, ${s.streamer.trees.points} points, ${s.streamer.trees.terminals} from terminals${s.streamer.trees.edited ? ` (${s.streamer.trees.edited} edited ones far away)` : ''}`,
            `downloaded ${(s.traffic.bytes / MiB).toFixed(2)} MiB in ${s.traffic.requests} requests (${s.traffic.errors} errors)`,
            `cache ${s.cache.entries} payloads, ${(s.cache.bytes / MiB).toFixed(1)} of ${(s.cache.budget / MiB).toFixed(0)} MiB, ${s.cache.evictions} evicted`,
            `requests pending ${s.pending}, in flight ${s.inFlight}, aborted ${s.aborted}`,
            `meshes ${s.meshes}   impostors ${s.impostors}   trees ${s.trees}`,
            s.loadTime !== null ? `first view complete in ${s.loadTime.toFixed(2)} s` : 'loading the first view...',
            `versions: ${s.versions.length ? s.versions.map((v) => `(${v.cell})/${v.grammar} v${v.version}`).join(' ') : 'all v1'}${lastEdit(s.lastEdit)}`,
        ];
        this.element.textContent = lines.join('\n');
    }
}
