// LOD0 from an extruded set: every building's base volume as a prism over its footprint ring
// (walls from the base elevation up by its height, a flat roof), in cell-local float
// coordinates (the cell group carries the camera-relative offset). Walls take the building's
// wall-material colour (the palette of render/src/base_volume_mesh.cpp) and a procedural
// window pattern whose storey height and bay width come from the building's own parameters
// (floor_h, and tile_w or module_w when its grammar declares them), so a parameter edit shows
// even at LOD0. Terminal cells draw the same volumes inset behind their terminals, without
// windows, so no gap in the facade shows the sky.
import * as THREE from 'three';

import { insetRing } from './polygon_inset.js';

const WALL_COLOURS = [
    [150, 124, 96], [120, 60, 40], [170, 160, 140], [90, 96, 104],
    [140, 110, 80], [110, 100, 90], [160, 140, 120], [70, 70, 75],
].map((c) => c.map((v) => (v / 255) ** 2.2)); // sRGB palette to linear
export const EXTRUDED_ROOF_COLOUR = [60, 58, 56].map((v) => (v / 255) ** 2.2);

// The window pattern (makeExtrudedMaterial): the glass, how far a window darkens the wall
// toward it, and where a window lies in its bay, across and up (fractions of the bay).
const WINDOW_GLASS = [0.06, 0.08, 0.11];
const WINDOW_MIX = 0.85;
const WINDOW_ACROSS = [0.22, 0.78];
const WINDOW_UP = [0.3, 0.82];
const WINDOW_SHARE = (WINDOW_ACROSS[1] - WINDOW_ACROSS[0]) * (WINDOW_UP[1] - WINDOW_UP[0]);
const DEFAULT_FLOOR_H = 3; // a storey, and a bay, where the grammar declares none

// The linear wall colour of wall material `material`.
export function wallColourOf(material) {
    return WALL_COLOURS[material % WALL_COLOURS.length];
}

// A wall's colour where its window bays are under a pixel: the pattern's mean over a wall of
// `height` metres whose storeys are `floorH` (the pattern leaves the lowest half storey bare).
export function wallTextureMean(wall, height, floorH = DEFAULT_FLOOR_H) {
    const windowed = height > 0 ? Math.min(Math.max(1 - (0.5 * floorH) / height, 0), 1) : 0;
    return wall.map((v, k) => v + (WINDOW_GLASS[k] - v) * WINDOW_MIX * WINDOW_SHARE * windowed);
}

// Building `i`'s footprint ring as [x, y] pairs, inset by `inset` metres, or null where it
// has no base volume (under three vertices, or no height).
export function extrudedRing(set, i, inset = 0) {
    const b = set.buildings;
    const n = b.vertexCount[i];
    if (n < 3 || !(b.height[i] > 0)) return null;
    let ring = [];
    for (let k = 0; k < n; ++k) ring.push([set.footprints.x[b.firstVertex[i] + k], set.footprints.y[b.firstVertex[i] + k]]);
    if (inset > 0) ring = insetRing(ring, inset);
    return ring.length < 3 ? null : ring;
}

// The buildings' storey heights where their grammar declares `floor_h`, else null.
export function floorHeights(set, grammar) {
    return grammar ? parameterColumn(set, grammar, ['floor_h']) : null;
}

function parameterColumn(set, grammar, names) {
    for (const name of names) {
        const j = grammar.parameters.findIndex((p) => p.name === name);
        if (j >= 0 && j < set.parametersPerBuilding) return set.parameters[j];
    }
    return null;
}

// {geometry, buildingOfTriangle}: one indexed triangle list for the whole batch, a wall's
// quad four vertices and a roof its ring's. Attributes are as small as their values allow
// (normals in bytes, colours in 16 bits: 41 bytes a vertex against 56 in floats), since every
// extruded cell in view stays resident.
export function buildExtrudedGeometry(set, grammar, { inset = 0, windows = true } = {}) {
    const b = set.buildings;
    const floorH = floorHeights(set, grammar);
    const bay = parameterColumn(set, grammar, ['tile_w', 'module_w']);
    const positions = [], normals = [], colours = [], facade = [], grid = [], index = [], triangleBuilding = [];
    const push = (x, y, z, n, c, u, v, wall, i) => {
        positions.push(x, y, z);
        normals.push(n[0] * 127, n[1] * 127, n[2] * 127);
        colours.push(c[0] * 65535, c[1] * 65535, c[2] * 65535);
        facade.push(u, v, wall);
        grid.push(floorH ? floorH[i] : DEFAULT_FLOOR_H, bay ? bay[i] : DEFAULT_FLOOR_H);
        return positions.length / 3 - 1;
    };
    for (let i = 0; i < b.count; ++i) {
        const ring = extrudedRing(set, i, inset);
        if (!ring) continue;
        const z0 = b.baseElevation[i], z1 = z0 + b.height[i];
        const wall = wallColourOf(b.wallMaterial[i]);
        const id = b.id[i];
        const w = windows ? 1 : 0;
        let along = 0;
        for (let k = 0; k < ring.length; ++k) {
            const [ax, ay] = ring[k], [bx, by] = ring[(k + 1) % ring.length];
            const length = Math.hypot(bx - ax, by - ay);
            if (!(length > 0)) continue;
            const normal = [(by - ay) / length, -(bx - ax) / length, 0];
            const a0 = push(ax, ay, z0, normal, wall, along, 0, w, i);
            const b0 = push(bx, by, z0, normal, wall, along + length, 0, w, i);
            const b1 = push(bx, by, z1, normal, wall, along + length, z1 - z0, w, i);
            const a1 = push(ax, ay, z1, normal, wall, along, z1 - z0, w, i);
            index.push(a0, b0, b1, a0, b1, a1); // counter-clockwise seen from outside
            triangleBuilding.push(id, id);
            along += length;
        }
        const first = push(ring[0][0], ring[0][1], z1, [0, 0, 1], EXTRUDED_ROOF_COLOUR, 0, 0, 0, i);
        for (let k = 1; k < ring.length; ++k) push(ring[k][0], ring[k][1], z1, [0, 0, 1], EXTRUDED_ROOF_COLOUR, 0, 0, 0, i);
        const contour = ring.map(([x, y]) => new THREE.Vector2(x, y));
        for (const [p, q, r] of THREE.ShapeUtils.triangulateShape(contour, [])) {
            index.push(first + p, first + q, first + r);
            triangleBuilding.push(id);
        }
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
    geometry.setAttribute('normal', new THREE.BufferAttribute(Int8Array.from(normals, Math.round), 3, true));
    geometry.setAttribute('color', new THREE.BufferAttribute(Uint16Array.from(colours, Math.round), 3, true));
    geometry.setAttribute('facade', new THREE.Float32BufferAttribute(facade, 3));
    geometry.setAttribute('windowGrid', new THREE.Float32BufferAttribute(grid, 2));
    geometry.setIndex(index); // 16-bit indices while the vertices allow (three.js chooses)
    geometry.computeBoundingSphere();
    return { geometry, buildingOfTriangle: Uint32Array.from(triangleBuilding) };
}

// Lambert walls with a window grid: a storey of floor_h, a bay of the bay width, a window in
// the middle 55 % of each bay between sill and lintel, darker and a little bluish.
export function makeExtrudedMaterial() {
    const material = new THREE.MeshLambertMaterial({ vertexColors: true });
    material.onBeforeCompile = (shader) => {
        shader.vertexShader = shader.vertexShader
            .replace('#include <common>', '#include <common>\nattribute vec3 facade;\nattribute vec2 windowGrid;\nvarying vec3 vFacade;\nvarying vec2 vWindowGrid;')
            .replace('#include <begin_vertex>', '#include <begin_vertex>\nvFacade = facade;\nvWindowGrid = windowGrid;');
        shader.fragmentShader = shader.fragmentShader
            .replace('#include <common>', '#include <common>\nvarying vec3 vFacade;\nvarying vec2 vWindowGrid;')
            .replace(
                '#include <color_fragment>',
                `#include <color_fragment>
                if (vFacade.z > 0.5 && vFacade.y > 0.5 * vWindowGrid.x) {
                    vec2 cell = vec2(vFacade.x / max(vWindowGrid.y, 0.5), vFacade.y / max(vWindowGrid.x, 0.5));
                    vec2 f = fract(cell);
                    float window = step(${WINDOW_ACROSS[0]}, f.x) * step(f.x, ${WINDOW_ACROSS[1]}) * step(${WINDOW_UP[0]}, f.y) * step(f.y, ${WINDOW_UP[1]});
                    diffuseColor.rgb = mix(diffuseColor.rgb, vec3(${WINDOW_GLASS.join(', ')}), window * ${WINDOW_MIX});
                }`,
            );
    };
    return material;
}
