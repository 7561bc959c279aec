// Moves every edge of a counter-clockwise ring inward by `distance` and joins neighbouring edges
// at their intersection (a mitre), for the base volumes drawn behind terminal facades. Mitres
// of very sharp corners are clamped to 4x the distance; a ring that would invert is returned
// as it was, which only costs a little z-fighting on a tiny building.
export function insetRing(ring, distance) {
    const n = ring.length;
    const out = [];
    for (let i = 0; i < n; ++i) {
        const p = ring[(i + n - 1) % n], c = ring[i], q = ring[(i + 1) % n];
        const e1 = normalise(c[0] - p[0], c[1] - p[1]), e2 = normalise(q[0] - c[0], q[1] - c[1]);
        // Inward normals of a CCW ring point to the left of each edge.
        const n1 = [-e1[1], e1[0]], n2 = [-e2[1], e2[0]];
        const bisector = normalise(n1[0] + n2[0], n1[1] + n2[1]);
        const cos = bisector[0] * n2[0] + bisector[1] * n2[1];
        const reach = Math.min(distance / Math.max(cos, 1e-6), 4 * distance);
        out.push([c[0] + bisector[0] * reach, c[1] + bisector[1] * reach]);
    }
    return signedArea(out) > 0 ? out : ring;
}

function normalise(x, y) {
    const l = Math.hypot(x, y) || 1;
    return [x / l, y / l];
}

export function signedArea(ring) {
    let a = 0;
    for (let i = 0; i < ring.length; ++i) {
        const [x0, y0] = ring[i], [x1, y1] = ring[(i + 1) % ring.length];
        a += x0 * y1 - x1 * y0;
    }
    return 0.5 * a;
}
