// Impostor view conventions in JavaScript, for tests and for the shaders: the same maps as
// impostor/src/view_layout.cpp and impostor/shaders/impostor_views.glsl. Facades use the
// hemi-octahedral grid of grid x grid views: view (column c, row r) looks from
// decodeHemiOctahedral(p), p = (c, r) * 2 / (grid - 1) - 1, the view frame's up following shape
// +y. Tree species use the full-sphere octahedral grid: view (c, r) looks from
// decodeOctahedral(p), p = (c + 0.5, r + 0.5) * 2 / grid - 1, its up following +z. Tiles are
// row-major, row 0 on top. `sphere` is the layout's "sphere" field.
export const HEMISPHERE = 'hemi-octahedral';
export const FULL_SPHERE = 'octahedral';

export function decodeHemiOctahedral(px, py) {
    const x = 0.5 * (px + py), y = 0.5 * (px - py);
    return normalize([x, y, Math.max(0, 1 - Math.abs(x) - Math.abs(y))]);
}

export function decodeOctahedral(px, py) {
    const z = 1 - Math.abs(px) - Math.abs(py);
    if (z >= 0) return normalize([px, py, z]);
    return normalize([signOf(px) * (1 - Math.abs(py)), signOf(py) * (1 - Math.abs(px)), z]);
}

export function viewDirection(view, grid, sphere = HEMISPHERE) {
    const c = view % grid, r = Math.floor(view / grid);
    if (sphere === FULL_SPHERE) return decodeOctahedral(((c + 0.5) * 2) / grid - 1, ((r + 0.5) * 2) / grid - 1);
    const s = 2 / (grid - 1);
    return decodeHemiOctahedral(c * s - 1, r * s - 1);
}

export function viewBasis(forward, sphere = HEMISPHERE) {
    const [primary, secondary] = sphere === FULL_SPHERE ? [[0, 0, 1], [0, 1, 0]] : [[0, 1, 0], [0, 0, 1]];
    const along = primary[0] * forward[0] + primary[1] * forward[1] + primary[2] * forward[2];
    const reference = Math.abs(along) > 0.999 ? secondary : primary;
    const right = normalize(cross(reference, forward));
    return { right, up: cross(forward, right), forward };
}

// The atlas texel (x, y from the top) that view coordinates uv in [-1, 1]^2 of `view` land on.
export function atlasTexel(view, uv, layout) {
    const { grid, view_resolution: resolution, padding } = layout;
    const inner = resolution - 2 * padding;
    const tx = Math.min(Math.max(padding + (uv[0] * 0.5 + 0.5) * inner - 0.5, padding), padding + inner - 1);
    const ty = Math.min(Math.max(padding + (0.5 - uv[1] * 0.5) * inner - 0.5, padding), padding + inner - 1);
    return [(view % grid) * resolution + tx, Math.floor(view / grid) * resolution + ty];
}

// The sign with +1 at zero, as the C++ fold's `p >= 0 ? a : -a`.
function signOf(v) {
    return v >= 0 ? 1 : -1;
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
// Where a direction lies in the table's square (view_table.js), in [0, 1]^2; behind the wall
// is pulled onto the rim.
vec2 impostorTablePosition(vec3 d) {
    d.z = max(d.z, 0.0);
    if (d.x == 0.0 && d.y == 0.0 && d.z == 0.0) d.z = 1.0;
    vec2 p = d.xy / (abs(d.x) + abs(d.y) + abs(d.z));
    return vec2(p.x + p.y, p.x - p.y) * 0.5 + 0.5;
}
`;

// The same maps on the full sphere, for the tree species' billboards.
export const TREE_VIEWS_GLSL = /* glsl */ `
vec3 octDecode(vec2 p) {
    vec3 d = vec3(p, 1.0 - abs(p.x) - abs(p.y));
    if (d.z < 0.0) d.xy = vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0) * (1.0 - abs(p.yx));
    return normalize(d);
}
vec2 octEncode(vec3 d) {
    vec2 p = d.xy / (abs(d.x) + abs(d.y) + abs(d.z));
    if (d.z < 0.0) p = vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0) * (1.0 - abs(p.yx));
    return p;
}
vec3 treeViewDirection(float view, float grid) {
    vec2 cell = vec2(mod(view, grid), floor(view / grid));
    return octDecode((cell + 0.5) * (2.0 / grid) - 1.0);
}
void treeBasis(vec3 forward, out vec3 right, out vec3 up) {
    vec3 reference = abs(forward.z) > 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0);
    right = normalize(cross(reference, forward));
    up = cross(forward, right);
}
vec2 treeTablePosition(vec3 d) {
    return octEncode(d) * 0.5 + 0.5;
}
`;

// Sampling an atlas (both spheres): tiles = (grid, view resolution, padding); uv in [-1, 1]^2
// of the view's frame, up at the top of its tile. accumulateView adds a view's colour (the
// albedo atlas is premultiplied by coverage) and its normal and depth (normal.png: n * 0.5 + 0.5,
// depth * 0.5 + 0.5) weighted by coverage.
export const IMPOSTOR_ATLAS_GLSL = /* glsl */ `
vec2 atlasUv(float view, vec2 uv, vec3 tiles) {
    float grid = tiles.x, resolution = tiles.y, padding = tiles.z;
    float inner = resolution - 2.0 * padding;
    vec2 texel = padding + vec2(uv.x * 0.5 + 0.5, 0.5 - uv.y * 0.5) * inner - 0.5;
    texel = clamp(texel, vec2(padding), vec2(padding + inner - 1.0));
    vec2 tile = vec2(mod(view, grid), floor(view / grid)) * resolution;
    return (tile + texel + 0.5) / (grid * resolution);
}
void accumulateView(sampler2D albedoAtlas, sampler2D normalAtlas, vec3 tiles, float view, vec2 uv, float weight,
                    inout vec4 colour, inout vec4 normalDepth) {
    if (weight <= 0.0 || abs(uv.x) > 1.0 || abs(uv.y) > 1.0) return;
    vec2 at = atlasUv(view, uv, tiles);
    vec4 a = texture2D(albedoAtlas, at);
    vec4 n = texture2D(normalAtlas, at) * 2.0 - 1.0;
    colour += weight * a;
    normalDepth += weight * a.a * n;
}
void accumulateViews(sampler2D albedoAtlas, sampler2D normalAtlas, vec3 tiles, vec4 views, vec4 weights, vec2 uv0,
                     vec2 uv1, vec2 uv2, vec2 uv3, out vec4 colour, out vec4 normalDepth) {
    colour = vec4(0.0);
    normalDepth = vec4(0.0);
    accumulateView(albedoAtlas, normalAtlas, tiles, views.x, uv0, weights.x, colour, normalDepth);
    accumulateView(albedoAtlas, normalAtlas, tiles, views.y, uv1, weights.y, colour, normalDepth);
    accumulateView(albedoAtlas, normalAtlas, tiles, views.z, uv2, weights.z, colour, normalDepth);
    accumulateView(albedoAtlas, normalAtlas, tiles, views.w, uv3, weights.w, colour, normalDepth);
}
`;
