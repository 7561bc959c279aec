// One species' tree billboards in a batch as one merged mesh: four vertices per tree, each
// carrying the tree's base (cell-local) in `treeBase`, which is all that places a billboard
// (trees stand upright and unrotated; tree_impostors.js turns the quad to the camera). A tree
// thus costs 68 bytes (corners 8, bases 48, index 12) where ImpostorQuads, which keeps a whole
// matrix for its quad and for each vertex, costs 276: far trees' billboards are a large part of
// what a city's extruded cells hold. Like ImpostorQuads it is one draw, not instances, which
// software renderers pay for per instance.
import * as THREE from 'three';

import { geometryBytes } from './geometry_bytes.js';
import { quadCorners } from './impostor_quads.js';

export class TreeQuads extends THREE.Mesh {
    // `capacity`: the most trees it may draw; none is drawn until `show`.
    constructor(material, capacity) {
        const geometry = quadCorners(capacity);
        const bases = new THREE.BufferAttribute(new Float32Array(12 * capacity), 3);
        bases.setUsage(THREE.DynamicDrawUsage);
        geometry.setAttribute('treeBase', bases);
        super(geometry, material);
        this.capacity = capacity;
        this.frustumCulled = false; // the cell's bounds decide visibility
        this.show(0);
    }

    // Places billboard `slot` at the base bases[offset .. offset + 3].
    place(slot, bases, offset) {
        const out = this.geometry.attributes.treeBase.array;
        for (let v = 0; v < 4; ++v) out.set(bases.subarray(offset, offset + 3), 12 * slot + 3 * v);
    }

    // Draws the first `count` billboards placed, and uploads their bases.
    show(count) {
        this.count = count;
        this.geometry.attributes.treeBase.needsUpdate = true;
    }

    // The billboards drawn, as ImpostorQuads' `count` (THREE.Mesh sets it to 1 before this
    // constructor has a capacity, which then sets 0).
    get count() {
        return this.geometry.drawRange.count / 6;
    }
    set count(quads) {
        this.geometry.setDrawRange(0, 6 * Math.max(0, Math.min(quads, this.capacity)));
    }

    // Bytes held for the GPU.
    get bytes() {
        return geometryBytes(this.geometry);
    }

    dispose() {
        this.geometry.dispose();
    }
}
