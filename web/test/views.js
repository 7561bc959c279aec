// Views for the tests of lod_policy's view test: a camera at the origin looking along a
// horizontal unit direction with a 90 degree frustum each way, as its four side planes (normals
// inward, through the camera) in the order of three.js's Frustum.planes[0..3].
export function viewAlong(forward) {
    const [fx, fy] = forward;
    const right = [fy, -fx, 0], up = [0, 0, 1];
    const s = Math.SQRT1_2;
    const plane = (sign, axis) => ({
        normal: [0, 1, 2].map((k) => s * (forward[k] + sign * axis[k])),
        constant: 0,
    });
    return { sides: [plane(-1, right), plane(1, right), plane(-1, up), plane(1, up)], forward, key: 'test' };
}

export const degrees = (d) => (d * Math.PI) / 180;
