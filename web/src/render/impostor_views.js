// Impostor view conventions in JavaScript, for tests and for the shader below: the same maps as
// impostor/src/view_layout.cpp and impostor/shaders/impostor_views.glsl (hemi-octahedral grid
// of grid x grid views; view (column c, row r) looks from decodeHemiOctahedral(p), p = (c, r) *
// 2 / (grid - 1) - 1; the view frame's up follows shape +y; tiles row-major, row 0 on top).
export function decodeHemiOctahedral(px, py) {
    const x = 0.5 * (px + py), y = 0.5 * (px - py);
    return normalize([x, y, Math.max(0, 1 - Math.abs(x) - Math.abs(y))]);
}

export function encodeHemiOctahedral(d) {
    const l1 = Math.abs(d[0]) + Math.abs(d[1]) + Math.abs(d[2]);
    const x = d[0] / l1, y = d[1] / l1;
    return [x + y, x - y];
}

export function viewDirection(view, grid) {
    const c = view % grid, r = Math.floor(view / grid), s = 2 / (grid - 1);
    return decodeHemiOctahedral(c * s - 1, r * s - 1);
}

// The continuous (column, row) of a direction; behind the wall (z < 0) is pulled onto the rim.
export function gridPosition(direction, grid) {
    let d = [direction[0], direction[1], Math.max(direction[2], 0)];
    if (d[0] === 0 && d[1] === 0 && d[2] === 0) d = [0, 0, 1];
    const p = encodeHemiOctahedral(d);
    return [(p[0] + 1) * 0.5 * (grid - 1), (p[1] + 1) * 0.5 * (grid - 1)];
}

export function viewBasis(forward) {
    const reference = Math.abs(forward[1]) > 0.999 ? [0, 0, 1] : [0, 1, 0];
    const right = normalize(cross(reference, forward));
    return { right, up: cross(forward, right), forward };
}

// The four views around a direction and their bilinear weights on the grid (the LOD3 blend).
export function blendViews(direction, grid) {
    const [gx, gy] = gridPosition(direction, grid);
    const c = Math.min(Math.max(Math.floor(gx), 0), grid - 2), r = Math.min(Math.max(Math.floor(gy), 0), grid - 2);
    const fx = gx - c, fy = gy - r;
    return {
        views: [r * grid + c, r * grid + c + 1, (r + 1) * grid + c, (r + 1) * grid + c + 1],
        weights: [(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy],
    };
}

// The atlas texel (x, y from the top) that view coordinates uv in [-1, 1]^2 of `view` land on.
export function atlasTexel(view, uv, layout) {
    const { grid, view_resolution: resolution, padding } = layout;
    const inner = resolution - 2 * padding;
    const tx = Math.min(Math.max(padding + (uv[0] * 0.5 + 0.5) * inner - 0.5, padding), padding + inner - 1);
    const ty = Math.min(Math.max(padding + (0.5 - uv[1] * 0.5) * inner - 0.5, padding), padding + inner - 1);
    return [(view % grid) * resolution + tx, Math.floor(view / grid) * resolution + ty];
}

function cross(a, b) {
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

function normalize(v) {
    const l = Math.hypot(v[0], v[1], v[2]) || 1;
    return [v[0] / l, v[1] / l, v[2] / l];
}

// The GLSL of the same maps, for the impostor material.
export const IMPOSTOR_VIEWS_GLSL = /* glsl */ `
vec3 hemiDecode(vec2 p) {
    float x = 0.5 * (p.x + p.y), y = 0.5 * (p.x - p.y);
    return normalize(vec3(x, y, max(0.0, 1.0 - abs(x) - abs(y))));
}
vec3 impostorViewDirection(float view, float grid) {
    vec2 cell = vec2(mod(view, grid), floor(view / grid));
    return hemiDecode(cell * (2.0 / (grid - 1.0)) - 1.0);
}
void impostorBasis(vec3 forward, out vec3 right, out vec3 up) {
    vec3 reference = abs(forward.y) > 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(0.0, 1.0, 0.0);
    right = normalize(cross(reference, forward));
    up = cross(forward, right);
}
vec2 impostorGridPosition(vec3 d, float grid) {
    d.z = max(d.z, 0.0);
    if (d.x == 0.0 && d.y == 0.0 && d.z == 0.0) d.z = 1.0;
    vec2 p = d.xy / (abs(d.x) + abs(d.y) + abs(d.z));
    return (vec2(p.x + p.y, p.x - p.y) + 1.0) * (0.5 * (grid - 1.0));
}
`;
