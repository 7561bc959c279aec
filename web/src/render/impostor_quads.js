// Impostor quads as one merged, non-instanced mesh: four vertices per quad, each carrying its
// quad's matrix. It stands in for an InstancedMesh of a 4-vertex quad (the same `count`,
// `setMatrixAt` and `instanceMatrix.array` / `needsUpdate`), because software renderers pay a
// fixed cost per instance: on SwiftShader 51,200 instances of a quad took 690 ms a frame, the
// same vertices as one instance 45 ms (web/bench/frame_cost.mjs measures the viewer's split).
// The vertex shader reads the matrix from `quadX`, `quadY`, `quadZ`: the matrix's first three
// columns in xyz and its translation spread over their w (see QUAD_MATRIX_GLSL).
import * as THREE from 'three';

import { geometryBytes } from './geometry_bytes.js';

// The quad's corners in the plane z = 0, as THREE.PlaneGeometry(2, 2) lays them out.
const CORNERS = [-1, 1, 1, 1, -1, -1, 1, -1];
const TRIANGLES = [0, 2, 1, 2, 3, 1];

// A geometry of `quads` quads' corners, four vertices each, as a `position` attribute of two
// bytes a vertex (the shaders read position.xy; z is 0) and their triangles' index, in 16 bits
// while the vertices allow. Where a quad stands is in attributes of its user's, so three.js
// cannot bound it from `position` (two components: the sphere it would compute is NaN, with an
// error logged, when it sorts the mesh): its bounding sphere is the cell's origin, unbounded.
export function quadCorners(quads) {
    const positions = new Int8Array(8 * quads);
    const index = new (4 * quads <= 65536 ? Uint16Array : Uint32Array)(6 * quads);
    for (let q = 0; q < quads; ++q) {
        positions.set(CORNERS, 8 * q);
        for (let k = 0; k < 6; ++k) index[6 * q + k] = 4 * q + TRIANGLES[k];
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 2));
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    geometry.boundingSphere = new THREE.Sphere(new THREE.Vector3(), Infinity);
    return geometry;
}

// GLSL: the quad's matrix, as InstancedMesh's `instanceMatrix` would give it.
export const QUAD_MATRIX_GLSL = /* glsl */ `
in vec4 quadX, quadY, quadZ;
mat4 quadMatrix() {
    return mat4(vec4(quadX.xyz, 0.0), vec4(quadY.xyz, 0.0), vec4(quadZ.xyz, 0.0), vec4(quadX.w, quadY.w, quadZ.w, 1.0));
}
`;

// The per-quad matrices, written as an InstancedMesh's are (after ImpostorQuads.reserve);
// `needsUpdate` spreads the first `count` of them over their vertices.
class QuadMatrices {
    constructor(mesh) {
        this.mesh = mesh;
        this.array = new Float32Array(0);
    }
    set needsUpdate(value) {
        if (value) this.mesh.spread(0, this.mesh.count);
    }
}

function quadGeometry(quads, old) {
    const geometry = quadCorners(quads);
    for (const name of ['quadX', 'quadY', 'quadZ']) {
        const array = new Float32Array(16 * quads);
        if (old) array.set(old.attributes[name].array);
        const attribute = new THREE.BufferAttribute(array, 4);
        attribute.setUsage(THREE.DynamicDrawUsage);
        geometry.setAttribute(name, attribute);
    }
    if (old) geometry.setDrawRange(old.drawRange.start, old.drawRange.count);
    return geometry;
}

// A merged mesh of quads (quadCorners' six indices each) drawing the first `count` of at most
// `capacity`: ImpostorQuads and tree_quads.js's TreeQuads. `count` stands where an
// InstancedMesh's would, so what reads one reads the other. Not frustum culled: the cell's
// bounds decide what is visible. None to draw: not drawn at all (three.js would still bind the
// program and issue an empty draw).
export class QuadMesh extends THREE.Mesh {
    constructor(geometry, material, capacity) {
        super(geometry, material); // which sets `count` (to 1) before there is a capacity: 0
        this.capacity = capacity;
        this.frustumCulled = false;
    }

    get count() {
        return this.geometry.drawRange.count / 6;
    }
    set count(quads) {
        this.geometry.setDrawRange(0, 6 * Math.max(0, Math.min(quads, this.capacity ?? 0)));
        this.visible = this.geometry.drawRange.count > 0;
    }
}

export class ImpostorQuads extends QuadMesh {
    // `capacity`: the most quads it may draw. Its matrices and vertices grow with the quads it
    // has drawn, as most terminals of a batch are never at this LOD.
    constructor(material, capacity) {
        super(quadGeometry(0, null), material, capacity);
        this.instanceMatrix = new QuadMatrices(this);
        this.count = capacity;
    }

    // Bytes held for the GPU: the quads' matrices and the vertices grown so far.
    get bytes() {
        return this.instanceMatrix.array.byteLength + geometryBytes(this.geometry);
    }

    // Room for quads [0, quads): matrices and vertices grow together, at least doubling, up to
    // the capacity; what they held is kept.
    reserve(quads) {
        const held = this.instanceMatrix.array.length / 16;
        if (quads <= held || held >= this.capacity) return;
        const size = Math.min(this.capacity, Math.max(quads, 2 * held, 64));
        const grown = new Float32Array(16 * size);
        grown.set(this.instanceMatrix.array);
        this.instanceMatrix.array = grown;
        const old = this.geometry;
        this.geometry = quadGeometry(size, old);
        old.dispose();
    }

    setMatrixAt(quad, matrix) {
        this.reserve(quad + 1);
        this.instanceMatrix.array.set(matrix.elements, 16 * quad);
        this.spread(quad, quad + 1);
    }

    // Copies quads [first, end) from the matrices to their four vertices each.
    spread(first, end) {
        end = Math.min(end, this.capacity);
        this.reserve(end);
        const m = this.instanceMatrix.array;
        const columns = ['quadX', 'quadY', 'quadZ'].map((name) => this.geometry.attributes[name]);
        for (let c = 0; c < 3; ++c) {
            const out = columns[c].array;
            for (let q = first; q < end; ++q) {
                const o = 16 * q;
                const x = m[o + 4 * c], y = m[o + 4 * c + 1], z = m[o + 4 * c + 2], w = m[o + 12 + c];
                for (let v = 0; v < 4; ++v) {
                    const at = 16 * q + 4 * v;
                    out[at] = x;
                    out[at + 1] = y;
                    out[at + 2] = z;
                    out[at + 3] = w;
                }
            }
            columns[c].needsUpdate = true;
        }
    }

    dispose() {
        this.geometry.dispose();
    }
}
