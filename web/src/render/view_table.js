// Which impostor views to blend for a direction, and how much of each, as the native renderer
// decides it (impostor/include/hexlod/impostor/view_lookup.h): of the five views nearest the
// direction, each of the four nearest gets the share 1/d - 1/d5 of their sum, less a floor of
// MIN_VIEW_SHARE, normalised; weights come largest first and a view below the floor drops out.
// The shaders read it from a table over the (hemi-)octahedral square, nearest texel, at the
// native tables' sizes, so the viewer blends the same views with the same weights as
// `hexlod walk`. Where one view dominates, the others weigh 0 and the fragment shader skips
// their texture reads, which a software rasteriser pays for per pixel.
import * as THREE from 'three';

import { decodeHemiOctahedral, decodeOctahedral, FULL_SPHERE, viewDirection } from './impostor_views.js';

const MIN_VIEW_SHARE = 0.2;
// view_lookup.h: kFacadeTableResolution, kSpeciesTableResolution.
export const FACADE_TABLE_RESOLUTION = 128;
export const SPECIES_TABLE_RESOLUTION = 64;

// The views and weights for unit `direction` among `directions` (3 numbers per view): views
// nearest first, weights summing to 1 (0 past `count`). On the hemisphere a direction behind
// the wall is pulled onto the rim.
export function nearestViews(direction, directions, sphere) {
    let [x, y, z] = direction;
    if (sphere !== FULL_SPHERE && z < 0) {
        const rim = Math.hypot(x, y);
        [x, y, z] = rim > 1e-6 ? [x / rim, y / rim, 0] : [0, 0, 1];
    }
    const count = directions.length / 3;
    const wanted = Math.min(5, count);
    // The `wanted` nearest by squared distance, kept sorted; ties keep the lower index first.
    const nearest = [0, 0, 0, 0, 0], squared = [Infinity, Infinity, Infinity, Infinity, Infinity];
    for (let v = 0; v < count; ++v) {
        const dx = x - directions[3 * v], dy = y - directions[3 * v + 1], dz = z - directions[3 * v + 2];
        const s = dx * dx + dy * dy + dz * dz;
        if (s >= squared[wanted - 1]) continue;
        let at = wanted - 1;
        for (; at > 0 && squared[at - 1] > s; --at) {
            squared[at] = squared[at - 1];
            nearest[at] = nearest[at - 1];
        }
        squared[at] = s;
        nearest[at] = v;
    }
    const blended = Math.min(4, wanted);
    const views = [0, 1, 2, 3].map((i) => nearest[Math.min(i, blended - 1)]);
    if (Math.sqrt(squared[0]) < 1e-6) return { views, weights: [1, 0, 0, 0], count: 1 };
    const cutoff = wanted > 4 ? 1 / Math.sqrt(squared[4]) : 0;
    let weights = [0, 0, 0, 0];
    for (let i = 0; i < blended; ++i) weights[i] = Math.max(0, 1 / Math.sqrt(squared[i]) - cutoff);
    let total = weights.reduce((a, b) => a + b);
    if (!(total > 0)) {
        // Four views tied with the fifth: equal shares.
        weights = weights.map((_, i) => (i < blended ? 1 / blended : 0));
        total = 1;
    }
    weights = weights.map((w) => Math.max(0, w / total - MIN_VIEW_SHARE));
    const kept = weights.reduce((a, b) => a + b);
    weights = weights.map((w) => w / kept);
    return { views, weights, count: weights.filter((w) => w > 0).length };
}

// The table over the square: texel (x, y) holds the blend for the direction at its centre, as
// ViewLookup::buildTable. `layout` is a scene's impostor layout (grid, sphere). A RangeError
// for a grid outside the layouts' [2, 32] (view_layout.h), which a service never sends.
export function buildViewTable(layout, resolution) {
    const { grid, sphere } = layout;
    if (!Number.isInteger(grid) || grid < 2 || grid > 32) throw new RangeError(`impostor layout grid ${grid} is outside [2, 32]`);
    const directions = [];
    for (let v = 0; v < grid * grid; ++v) directions.push(...viewDirection(v, grid, sphere));
    const views = new Float32Array(resolution * resolution * 4);
    const weights = new Float32Array(resolution * resolution * 4);
    for (let y = 0; y < resolution; ++y) {
        for (let x = 0; x < resolution; ++x) {
            const px = ((x + 0.5) / resolution) * 2 - 1, py = ((y + 0.5) / resolution) * 2 - 1;
            const d = sphere === FULL_SPHERE ? decodeOctahedral(px, py) : decodeHemiOctahedral(px, py);
            const blend = nearestViews(d, directions, sphere);
            views.set(blend.views, (y * resolution + x) * 4);
            weights.set(blend.weights, (y * resolution + x) * 4);
        }
    }
    return { resolution, views, weights };
}

// The table as the two textures the shaders read with texelFetch (uniforms of VIEW_TABLE_GLSL).
export function viewTableUniforms(table) {
    const texture = (data) => {
        const t = new THREE.DataTexture(data, table.resolution, table.resolution, THREE.RGBAFormat, THREE.FloatType);
        t.minFilter = t.magFilter = THREE.NearestFilter;
        t.needsUpdate = true;
        return t;
    };
    return { viewTableViews: { value: texture(table.views) }, viewTableWeights: { value: texture(table.weights) } };
}

// The table's uniforms for a scene's layout, or null with the reason pushed onto `failed` (the
// caller then draws no impostors of that layout, and its status says why).
export function layoutTableUniforms(layout, resolution, failed) {
    try {
        return viewTableUniforms(buildViewTable(layout, resolution));
    } catch (e) {
        failed.push(e.message);
        return null;
    }
}

// tableBlend(position): the views and weights at a position in [0, 1]^2 of the table's square
// (impostorTablePosition or treeTablePosition of impostor_views.js), nearest texel.
export const VIEW_TABLE_GLSL = /* glsl */ `
uniform sampler2D viewTableViews, viewTableWeights;
void tableBlend(vec2 position, out vec4 views, out vec4 weights) {
    ivec2 size = textureSize(viewTableWeights, 0);
    ivec2 texel = clamp(ivec2(position * vec2(size)), ivec2(0), size - 1);
    views = texelFetch(viewTableViews, texel, 0);
    weights = texelFetch(viewTableWeights, texel, 0);
}
`;
