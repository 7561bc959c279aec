// Extruded set, version 1 (docs/protocol.md): the 96-byte header and the zstd body of u32
// columns (per building, per footprint vertex, per facade element, then one column per grammar
// parameter), decoded as grammar/src/extruded_set_codec.cpp does, with its validation. What
// LOD0 draws: base volumes (footprint ring, base elevation, height), a wall material, and the
// facade frames.
import { hex64 } from './checksum64.js';
import { MAX_DECODED_BYTES, openPayload, readU64, u64Number, unzigzagInPlace, verifyChecksum } from './format.js';
import { PayloadError } from './payload_error.js';
import { decompressFrame } from './zstd_frame.js';

export const EXTRUDED_SET_VERSION = 1;
export const EXTRUDED_HEADER_BYTES = 96;
const MAX_BUILDINGS = 2 ** 24;
const MAX_VERTICES = 2 ** 28;
const MAX_ELEMENTS = 2 ** 28;
const MAX_PARAMETERS = 4096;

// Reads the body's columns in order, undoing deltas where the format has them.
class ColumnReader {
    constructor(words) {
        this.words = words;
        this.at = 0;
    }
    column(count) {
        const out = this.words.slice(this.at, this.at + count);
        this.at += count;
        return out;
    }
    deltaColumn(count) {
        const out = this.column(count);
        unzigzagInPlace(out);
        return out;
    }
}

const asFloats = (words) => new Float32Array(words.buffer, words.byteOffset, words.length);

// The facade frames' columns: origin (delta-coded), two axes, size, rule and atom.
function readElements(r, count) {
    const origin = [0, 1, 2].map(() => asFloats(r.deltaColumn(count)));
    const axisX = [0, 1, 2].map(() => asFloats(r.column(count)));
    const axisY = [0, 1, 2].map(() => asFloats(r.column(count)));
    const size = [0, 1].map(() => asFloats(r.column(count)));
    return { count, origin, axisX, axisY, size, rule: r.column(count), atom: r.column(count) };
}

// `elements`: whether to keep the facade frames (13 words each: most of a batch's body).
// Without them `elements` holds only their count, and byteSize counts what is kept; the viewer
// draws nothing from them (LOD1, which ray-casts them, is native), so it leaves them out.
export function decodeExtrudedSet(payload, { elements = true } = {}) {
    const { bytes, view } = openPayload(payload, EXTRUDED_HEADER_BYTES, 'HXE1', 'an extruded set', EXTRUDED_SET_VERSION);
    const p = view.getUint32(28, true);
    const nb = view.getUint32(72, true), nv = view.getUint32(76, true), ne = view.getUint32(80, true);
    const bodyBytes = u64Number(readU64(view, 88));
    if (view.getUint32(84, true) !== 0) throw new PayloadError('reserved header word is not zero');
    if (nb > MAX_BUILDINGS || nv > MAX_VERTICES || ne > MAX_ELEMENTS || p > MAX_PARAMETERS)
        throw new PayloadError("counts exceed the format's limits");
    if (nb === 0 && p !== 0) throw new PayloadError('parameters per building without buildings');
    const available = bytes.length - EXTRUDED_HEADER_BYTES;
    if (available < bodyBytes)
        throw new PayloadError(`truncated: ${bytes.length} bytes, the header needs ${EXTRUDED_HEADER_BYTES + bodyBytes}`);
    if (available > bodyBytes) throw new PayloadError('trailing bytes after the body');
    const words = nb * (6 + p) + 2 * nv + 13 * ne;
    if (4 * words > MAX_DECODED_BYTES)
        throw new PayloadError(`an extruded set of ${4 * words} bytes is more than this viewer decodes in one batch`);
    const body = decompressFrame(bytes.subarray(EXTRUDED_HEADER_BYTES), 4 * words);
    const checksum = verifyChecksum(bytes, EXTRUDED_HEADER_BYTES, body);

    const r = new ColumnReader(new Uint32Array(body.buffer, body.byteOffset, words));
    const building = r.deltaColumn(nb);
    const vertexCount = r.column(nb);
    const elementCount = r.column(nb);
    const baseElevation = asFloats(r.column(nb));
    const height = asFloats(r.column(nb));
    const wallMaterial = r.column(nb);
    for (let i = 0; i < nb; ++i)
        if (wallMaterial[i] > 0xffff) throw new PayloadError('wall material outside 16 bits');
    const firstVertex = new Uint32Array(nb), firstElement = new Uint32Array(nb);
    let vertex = 0, element = 0;
    for (let i = 0; i < nb; ++i) {
        firstVertex[i] = vertex;
        firstElement[i] = element;
        vertex += vertexCount[i];
        element += elementCount[i];
    }
    if (vertex !== nv || element !== ne)
        throw new PayloadError(
            `buildings' vertex and element counts sum to ${vertex} and ${element}, the header says ${nv} and ${ne}`,
        );
    const footprintX = asFloats(r.deltaColumn(nv)), footprintY = asFloats(r.deltaColumn(nv));
    const frames = elements ? readElements(r, ne) : { count: ne };
    if (!elements) r.at += 13 * ne;
    const parameters = [];
    for (let j = 0; j < p; ++j) parameters.push(asFloats(r.column(nb)));
    return {
        kind: 'extruded-set',
        version: EXTRUDED_SET_VERSION,
        checksum,
        cell: { q: view.getInt32(16, true), r: view.getInt32(20, true) },
        grammar: view.getUint32(24, true),
        grammarHash: hex64(readU64(view, 32)),
        key: hex64(readU64(view, 40)),
        origin: [view.getFloat64(48, true), view.getFloat64(56, true), view.getFloat64(64, true)],
        buildings: { count: nb, id: building, vertexCount, elementCount, firstVertex, firstElement, baseElevation, height, wallMaterial },
        footprints: { x: footprintX, y: footprintY },
        elements: frames,
        parametersPerBuilding: p,
        parameters, // parameters[j][i]: parameter j (declaration order) of building i
        byteSize: 4 * (elements ? words : words - 13 * ne),
    };
}
