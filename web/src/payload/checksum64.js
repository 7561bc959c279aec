// checksum64 of the payload formats (docs/protocol.md, "Checksum"; grammar/src/terminal_set_codec.cpp):
// four XXH64-style lanes over 8-byte little-endian words, finished with splitmix64. Not XXH64.
// JavaScript has no fast 64-bit integers (BigInt allocates per operation, far too slow for a
// megabyte body), so every 64-bit value is a pair of uint32 halves and the arithmetic is spelled
// out on them. A value is returned as 16 lowercase hex digits, the way the API prints keys.

const P1 = [0x9e3779b1, 0x85ebca87];
const P2 = [0xc2b2ae3d, 0x27d4eb4f];
const P4 = [0x85ebca77, 0xc2b2ae63];
const P5 = [0x27d4eb2f, 0x165667c5];

// Scratch registers: results of the helpers land in `rh`, `rl` (high, low).
let rh = 0;
let rl = 0;

function add(ah, al, bh, bl) {
    const lo = (al >>> 0) + (bl >>> 0);
    rl = lo >>> 0;
    rh = (ah + bh + (lo > 0xffffffff ? 1 : 0)) >>> 0;
}

function sub(ah, al, bh, bl) {
    rl = (al - bl) >>> 0;
    rh = (ah - bh - ((al >>> 0) < (bl >>> 0) ? 1 : 0)) >>> 0;
}

// (a * b) mod 2^64, from 16-bit limbs of the low words (exact in doubles) plus the cross terms.
function mul(ah, al, bh, bl) {
    const a0 = al & 0xffff, a1 = al >>> 16, b0 = bl & 0xffff, b1 = bl >>> 16;
    let t = a0 * b0;
    const w0 = t & 0xffff;
    t = a1 * b0 + (t >>> 16);
    const w1 = t & 0xffff, w2 = Math.floor(t / 65536);
    t = a0 * b1 + w1;
    const hi = a1 * b1 + w2 + Math.floor(t / 65536);
    rl = (((t & 0xffff) << 16) | w0) >>> 0;
    rh = (hi + Math.imul(ah, bl) + Math.imul(al, bh)) >>> 0;
}

function rotl(h, l, n) {
    if (n >= 32) {
        const t = h;
        h = l;
        l = t;
        n -= 32;
    }
    if (n === 0) {
        rh = h >>> 0;
        rl = l >>> 0;
        return;
    }
    rh = ((h << n) | (l >>> (32 - n))) >>> 0;
    rl = ((l << n) | (h >>> (32 - n))) >>> 0;
}

// x ^ (x >> n) for 0 < n < 32.
function xorShift(h, l, n) {
    rl = (l ^ ((l >>> n) | (h << (32 - n)))) >>> 0;
    rh = (h ^ (h >>> n)) >>> 0;
}

// rotl(acc + w * P2, 31) * P1
function round(acch, accl, wh, wl) {
    mul(wh, wl, P2[0], P2[1]);
    add(acch, accl, rh, rl);
    rotl(rh, rl, 31);
    mul(rh, rl, P1[0], P1[1]);
}

// splitmix64's finaliser (grammar/include/hexlod/grammar/position_hash.h, mixBits).
function mixBits(h, l) {
    add(h, l, 0x9e3779b9, 0x7f4a7c15);
    xorShift(rh, rl, 30);
    mul(rh, rl, 0xbf58476d, 0x1ce4e5b9);
    xorShift(rh, rl, 27);
    mul(rh, rl, 0x94d049bb, 0x133111eb);
    xorShift(rh, rl, 31);
}

// `bytes`: a Uint8Array; `seed`: [high, low] uint32 halves. Returns [high, low].
export function checksum64(bytes, seed = [0, 0]) {
    const [sh, sl] = seed;
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    let n = bytes.byteLength;
    let p = 0;
    add(sh, sl, P5[0], P5[1]);
    let hh = rh, hl = rl;
    if (n >= 32) {
        add(sh, sl, P1[0], P1[1]);
        add(rh, rl, P2[0], P2[1]);
        const v = [rh, rl, 0, 0, sh >>> 0, sl >>> 0, 0, 0];
        add(sh, sl, P2[0], P2[1]);
        v[2] = rh;
        v[3] = rl;
        sub(sh, sl, P1[0], P1[1]);
        v[6] = rh;
        v[7] = rl;
        for (; n >= 32; n -= 32, p += 32) {
            for (let lane = 0; lane < 4; ++lane) {
                const wl = view.getUint32(p + 8 * lane, true), wh = view.getUint32(p + 8 * lane + 4, true);
                round(v[2 * lane], v[2 * lane + 1], wh, wl);
                v[2 * lane] = rh;
                v[2 * lane + 1] = rl;
            }
        }
        hh = 0;
        hl = 0;
        [1, 7, 12, 18].forEach((bits, lane) => {
            rotl(v[2 * lane], v[2 * lane + 1], bits);
            add(hh, hl, rh, rl);
            hh = rh;
            hl = rl;
        });
    }
    const size = bytes.byteLength;
    add(hh, hl, Math.floor(size / 4294967296), size >>> 0);
    hh = rh;
    hl = rl;
    for (; n >= 8; n -= 8, p += 8) {
        const wl = view.getUint32(p, true), wh = view.getUint32(p + 4, true);
        round(0, 0, wh, wl);
        rotl((hh ^ rh) >>> 0, (hl ^ rl) >>> 0, 27);
        mul(rh, rl, P1[0], P1[1]);
        add(rh, rl, P4[0], P4[1]);
        hh = rh;
        hl = rl;
    }
    for (; n > 0; --n, ++p) {
        mul(0, bytes[p], P5[0], P5[1]);
        rotl((hh ^ rh) >>> 0, (hl ^ rl) >>> 0, 11);
        mul(rh, rl, P1[0], P1[1]);
        hh = rh;
        hl = rl;
    }
    mixBits(hh, hl);
    return [rh, rl];
}

export function hex64([h, l]) {
    return h.toString(16).padStart(8, '0') + l.toString(16).padStart(8, '0');
}
