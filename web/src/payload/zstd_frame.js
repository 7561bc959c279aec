// One zstd frame of a payload body (RFC 8878), decompressed with fzstd (pure JavaScript) under
// the checks the C++ decoder makes (grammar/src/zstd_frame.cpp): the frame must be exactly one
// frame with nothing after it, declare (if it declares one) the size the header needs, and
// decode to exactly that many bytes. The frame is walked block by block first, so a truncated
// frame or trailing bytes are named before any decompression, and fzstd never runs on into a
// second frame.
import { decompress } from 'fzstd';

import { PayloadError } from './payload_error.js';

const MAGIC = 0xfd2fb528;

// The byte length of the zstd frame at the start of `bytes` and its declared content size
// (null when it declares none). Throws PayloadError for anything that is not a whole frame.
export function walkFrame(bytes) {
    if (bytes.length < 6) throw new PayloadError('body is not a zstd frame (too short)');
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    if (view.getUint32(0, true) !== MAGIC) throw new PayloadError('body is not a zstd frame');
    const descriptor = bytes[4];
    const singleSegment = (descriptor >> 5) & 1;
    const hasChecksum = (descriptor >> 2) & 1;
    const dictionaryBytes = [0, 1, 2, 4][descriptor & 3];
    const sizeFlag = descriptor >> 6;
    const sizeBytes = sizeFlag === 0 ? singleSegment : 1 << sizeFlag;
    if (descriptor & 8) throw new PayloadError('body is not a zstd frame (reserved bit set)');
    let at = 5 + (singleSegment ? 0 : 1) + dictionaryBytes;
    if (at + sizeBytes > bytes.length) throw new PayloadError('truncated body');
    let declared = null;
    if (sizeBytes === 1) declared = bytes[at];
    else if (sizeBytes === 2) declared = view.getUint16(at, true) + 256;
    else if (sizeBytes === 4) declared = view.getUint32(at, true);
    else if (sizeBytes === 8) declared = view.getUint32(at, true) + view.getUint32(at + 4, true) * 4294967296;
    at += sizeBytes;
    for (;;) {
        if (at + 3 > bytes.length) throw new PayloadError('truncated body');
        const header = bytes[at] | (bytes[at + 1] << 8) | (bytes[at + 2] << 16);
        const last = header & 1, type = (header >> 1) & 3, size = header >>> 3;
        if (type === 3) throw new PayloadError('corrupt body: reserved block type');
        at += 3 + (type === 1 ? 1 : size);
        if (at > bytes.length) throw new PayloadError('truncated body');
        if (last) break;
    }
    if (hasChecksum) at += 4;
    if (at > bytes.length) throw new PayloadError('truncated body');
    return { length: at, declared };
}

// Decompresses `frame` (a Uint8Array holding exactly one frame) to exactly `expected` bytes.
export function decompressFrame(frame, expected) {
    const { length, declared } = walkFrame(frame);
    if (length !== frame.length) throw new PayloadError('trailing bytes after the body');
    if (declared !== null && declared !== expected)
        throw new PayloadError(`body declares ${declared} bytes, the header needs ${expected}`);
    let body;
    try {
        body = decompress(frame);
    } catch (e) {
        throw new PayloadError(`corrupt body: ${e.message}`);
    }
    if (body.length !== expected)
        throw new PayloadError(`body decodes to ${body.length} bytes, the header needs ${expected}`);
    return body;
}
