// One species' tree billboards in a batch as one merged mesh: four vertices per tree, each
// carrying the tree's base (cell-local) in `treeBase`, which is all that places a billboard
// (trees stand upright and unrotated; tree_impostors.js turns the quad to the camera). A tree
// thus costs 68 bytes (corners 8, bases 48, index 12) where ImpostorQuads, which keeps a whole
// matrix for its quad and for each vertex, costs 276: far trees' billboards are a large part of
// what a city's extruded cells hold. Like ImpostorQuads it is one draw, not instances, which
// software renderers pay for per instance.
import * as THREE from 'three';

import { geometryBytes } from './geometry_bytes.js';
import { QuadMesh, quadCorners } from './impostor_quads.js';

export class TreeQuads extends QuadMesh {
    // `capacity`: the most trees it may draw; none is drawn until `show`.
    constructor(material, capacity) {
        const geometry = quadCorners(capacity);
        const bases = new THREE.BufferAttribute(new Float32Array(12 * capacity), 3);
        bases.setUsage(THREE.DynamicDrawUsage);
        geometry.setAttribute('treeBase', bases);
        super(geometry, material, capacity);
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

    // Bytes held for the GPU.
    get bytes() {
        return geometryBytes(this.geometry);
    }

    dispose() {
        this.geometry.dispose();
    }
}
