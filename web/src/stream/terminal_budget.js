// Which terminal sets the viewer may hold. The content cache evicts what a frame does not draw,
// but what it draws is pinned, so a view that wants more terminal sets than the budget holds
// grew past it without bound (the thesis city's street view held 0.9 GB against 384 MiB). As
// the native renderer's terminal arena does (sets beyond it draw at LOD1 or LOD0), the viewer
// admits the terminal sets a frame wants highest priority first (in view, then by screen-space
// error: the nearest first), each whose bytes fit in what the budget leaves after the content
// every frame pins anyway (extruded sets); a building batch whose set is not admitted draws its
// extruded set (LOD0), a tree batch its trees as billboards, and the set is neither fetched
// nor pinned.

// A set drawn now keeps its place against a rival whose priority is less than this much higher,
// so that a camera standing at the cut does not fetch and evict the same sets over and over.
export const DRAWN_PRIORITY_FACTOR = 1.25;

// Per grammar, the mean bytes per member (building or tree) of its terminal sets measured so
// far (`measured`: {grammar, members, bytes}, what a drawn set keeps and its GPU objects); 0 for
// a grammar with none. An unmeasured set thus costs nothing in the estimate: the fetch queue
// takes the admitted sets highest priority first, a few at a time, and the first one measured
// prices the rest of its grammar's. Members differ too much to price one grammar's by
// another's (at the thesis street a house took 37 KB, a tower 0.45 MB, a tree far less), and
// a guess that is too high holds sets back for good, since nothing held is ever measured.
export function bytesPerMember(measured) {
    const sums = new Map();
    for (const e of measured) {
        if (!(e.members > 0)) continue;
        const sum = sums.get(e.grammar) ?? { bytes: 0, members: 0 };
        sum.bytes += e.bytes;
        sum.members += e.members;
        sums.set(e.grammar, sum);
    }
    return (grammar) => {
        const sum = sums.get(grammar);
        return sum ? sum.bytes / sum.members : 0;
    };
}

// `candidates`: {url, priority, bytes, drawn}, bytes known (cached) or estimated. Returns the set
// of urls admitted: in priority order (drawn sets favoured by DRAWN_PRIORITY_FACTOR), each set
// whose bytes fit in what `room` has left. A set that does not fit is passed over and a smaller
// one after it may still take the room: in the thesis city a tower cell's set takes hundreds
// of megabytes, and stopping at it left a tight budget's room empty.
export function admitTerminalSets(candidates, room) {
    const rank = (c) => c.priority * (c.drawn ? DRAWN_PRIORITY_FACTOR : 1);
    const ordered = [...candidates].sort((a, b) => rank(b) - rank(a));
    const admitted = new Set();
    let used = 0;
    for (const c of ordered) {
        if (admitted.has(c.url) || !(used + c.bytes <= room)) continue;
        used += c.bytes;
        admitted.add(c.url);
    }
    return admitted;
}
