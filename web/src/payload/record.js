// One terminal record's packed fields as numbers (grammar/include/hexlod/grammar/terminal_set.h):
// position (3 x f32, relative to the cell origin), building id, orientation (unit quaternion
// x, y, z, w as 4 x snorm16), size (width, height as 2 x half), shape id (low 16 bits) and
// depth ratio (half, high 16). The conversions are those of lod/cull_shared.h.

const f32 = new Float32Array(1);
const u32 = new Uint32Array(f32.buffer);

export function halfToFloat(h) {
    const sign = (h & 0x8000) << 16;
    const exponent = (h >> 10) & 0x1f;
    const mantissa = h & 0x3ff;
    if (exponent === 0) {
        const value = mantissa * 5.9604644775390625e-8;
        return sign !== 0 ? -value : value;
    }
    if (exponent === 31) u32[0] = (sign | 0x7f800000 | (mantissa << 13)) >>> 0;
    else u32[0] = (sign | ((exponent + 112) << 23) | (mantissa << 13)) >>> 0;
    return f32[0];
}

export function snorm16ToFloat(bits) {
    const value = ((bits << 16) >> 16) / 32767;
    return value < -1 ? -1 : value;
}

// Record `i` of a decoded terminal set, unpacked (for picking, tests and tools; the renderer
// reads the words directly).
export function unpackRecord(set, i) {
    const w = set.records, b = 8 * i;
    const quaternion = [
        snorm16ToFloat(w[b + 4] & 0xffff),
        snorm16ToFloat(w[b + 4] >>> 16),
        snorm16ToFloat(w[b + 5] & 0xffff),
        snorm16ToFloat(w[b + 5] >>> 16),
    ];
    return {
        position: [set.positions[b], set.positions[b + 1], set.positions[b + 2]],
        building: w[b + 3],
        quaternion,
        size: [halfToFloat(w[b + 6] & 0xffff), halfToFloat(w[b + 6] >>> 16)],
        depthRatio: halfToFloat(w[b + 7] >>> 16),
        shape: w[b + 7] & 0xffff,
    };
}

// The scope axes X (along the facade), Y (up it), Z (out of it) of a quaternion [x, y, z, w],
// normalised first (snorm16 leaves it a little off unit length, which a matrix would show as
// a scale), as glm's mat3_cast. Returns nine numbers: X, then Y, then Z.
export function quaternionAxes(q, out = new Float64Array(9)) {
    let [x, y, z, w] = q;
    const length = Math.hypot(x, y, z, w) || 1;
    x /= length;
    y /= length;
    z /= length;
    w /= length;
    const xx = x * x, yy = y * y, zz = z * z, xy = x * y, xz = x * z, yz = y * z, wx = w * x, wy = w * y, wz = w * z;
    out[0] = 1 - 2 * (yy + zz);
    out[1] = 2 * (xy + wz);
    out[2] = 2 * (xz - wy);
    out[3] = 2 * (xy - wz);
    out[4] = 1 - 2 * (xx + zz);
    out[5] = 2 * (yz + wx);
    out[6] = 2 * (xz + wy);
    out[7] = 2 * (yz - wx);
    out[8] = 1 - 2 * (xx + yy);
    return out;
}
