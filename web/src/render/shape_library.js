// The LOD4 geometry of one grammar's terminal shapes, in unit scope space
// (render/include/hexlod/render/terminal_mesh.h: u, v in [0, 1] across and up the scope, t in
// [-1, 1] out of the wall, drawn by an instance matrix T·R·diag(w, h, d)). With the scene's
// `capabilities.terminal_meshes` each shape's glTF comes from its mesh_url (POSITION, NORMAL,
// COLOR_0 in unit space; node transforms applied, primitives merged); without it, or when a
// shape's mesh fails to load, the shape gets a stand-in: its scope's front face at full
// protrusion, coloured by what its name says it is. `status` says which, for the stats panel.
// A shape with a served `coarse_mesh` also gets that mesh's geometry as
// `coarse` ({geometry, deviation, triangles}), drawn where lod_policy.coarseMeshReach allows; it
// stays null without meshes or when that glTF fails to load (the shape's mesh is drawn then).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { mergeGeometries } from 'three/addons/utils/BufferGeometryUtils.js';

const STAND_IN_COLOURS = [
    [/glass|window|glazing|pane/, [0.16, 0.2, 0.26]],
    [/door|shutter/, [0.35, 0.22, 0.12]],
    [/roof|tile|chimney/, [0.42, 0.16, 0.12]],
    [/leaf|leaves|crown|foliage|canopy|needle/, [0.14, 0.36, 0.12]],
    [/bark|trunk|branch/, [0.3, 0.2, 0.12]],
    [/balcony|rail|ledge|cornice|sill|moulding|frame|pilaster/, [0.75, 0.72, 0.66]],
];

function standInColour(name) {
    for (const [pattern, colour] of STAND_IN_COLOURS) if (pattern.test(name)) return colour;
    let hash = 0;
    for (const c of name) hash = (Math.imul(hash, 31) + c.charCodeAt(0)) >>> 0;
    const grey = 0.45 + ((hash % 1000) / 1000) * 0.3;
    return [grey, grey * 0.97, grey * 0.93];
}

// The scope's front face, u, v in [0, 1] at its full protrusion t = 1 (t = 0 for flat shapes):
// two triangles, since a city holds hundreds of thousands of terminals and a stand-in is only
// there until real meshes are served.
export function standInGeometry(name, flat) {
    const geometry = new THREE.PlaneGeometry(1, 1);
    geometry.translate(0.5, 0.5, flat ? 0 : 1);
    const base = standInColour(name);
    const colours = new Float32Array(geometry.getAttribute('position').count * 3);
    for (let i = 0; i < colours.length; i += 3) colours.set(base, i);
    geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    geometry.deleteAttribute('uv');
    return geometry;
}

// One geometry (position, normal, color) from every mesh of a glTF scene, transforms applied.
export function mergeGltfScene(root) {
    const parts = [];
    root.updateMatrixWorld(true);
    root.traverse((node) => {
        if (!node.isMesh) return;
        let g = node.geometry.clone().applyMatrix4(node.matrixWorld);
        if (g.index) g = g.toNonIndexed();
        if (!g.getAttribute('normal')) g.computeVertexNormals();
        if (!g.getAttribute('color')) {
            const c = node.material?.color ?? new THREE.Color(1, 1, 1);
            const colours = new Float32Array(g.getAttribute('position').count * 3);
            for (let i = 0; i < colours.length; i += 3) colours.set([c.r, c.g, c.b], i);
            g.setAttribute('color', new THREE.BufferAttribute(colours, 3));
        }
        const kept = new THREE.BufferGeometry();
        for (const name of ['position', 'normal']) kept.setAttribute(name, g.getAttribute(name));
        // COLOR_0 may be RGBA and normalised bytes: keep rgb as floats.
        const colour = g.getAttribute('color');
        const rgb = new Float32Array(colour.count * 3);
        for (let i = 0; i < colour.count; ++i) rgb.set([colour.getX(i), colour.getY(i), colour.getZ(i)], 3 * i);
        kept.setAttribute('color', new THREE.BufferAttribute(rgb, 3));
        parts.push(kept);
    });
    if (parts.length === 0) throw new Error('the glTF holds no mesh');
    return mergeGeometries(parts, false);
}

export class ShapeLibrary {
    // `coarse`: false leaves coarse meshes out (every terminal draws its shape's mesh).
    constructor(grammar, { meshes, coarse = true }) {
        this.grammar = grammar;
        this.shapes = (grammar.shapes ?? []).map((s, i) => {
            const nominal = s.nominal_size ?? [s.width ?? 1, s.height ?? 1, s.depth ?? 0];
            return {
                index: s.index ?? s.id ?? i,
                name: s.name,
                nominal,
                meshUrl: s.mesh_url ?? null,
                coarseMesh: coarse ? (s.coarse_mesh ?? null) : null,
                coarse: null,
                impostor: s.impostor ?? null,
                geometry: standInGeometry(s.name, !(nominal[2] > 0)),
                source: 'stand-in',
            };
        });
        this.loaded = 0;
        this.failed = [];
        this.meshesServed = meshes;
        this.isReady = false;
        this.ready = (meshes ? this.loadMeshes() : Promise.resolve()).then(() => (this.isReady = true));
    }

    async loadMeshes() {
        const loader = new GLTFLoader();
        const load = async (url) => mergeGltfScene((await loader.loadAsync(url)).scene);
        await Promise.all(
            this.shapes.map(async (shape) => {
                if (!shape.meshUrl) return;
                try {
                    shape.geometry = await load(shape.meshUrl);
                    shape.source = 'glTF';
                    ++this.loaded;
                    const c = shape.coarseMesh;
                    if (c) shape.coarse = { geometry: await load(c.url), deviation: c.deviation, triangles: c.triangles };
                } catch (e) {
                    this.failed.push(`${shape.name}: ${e.message ?? e}`);
                }
            }),
        );
    }

    shape(index) {
        return this.shapes[index] ?? this.shapes.find((s) => s.index === index);
    }

    get status() {
        if (!this.meshesServed) return 'stand-ins';
        const failed = this.failed.length ? `, ${this.failed.length} failed` : '';
        return `${this.loaded}/${this.shapes.length} glTF${failed}`;
    }
}
