// An InstancedMesh whose instance buffer grows with the instances it has drawn, up to its
// capacity, as ImpostorQuads' vertices do: a sorted batch's LOD4 and coarse lists hold a few
// of its terminals, and a buffer as long as the batch would keep 64 bytes for each of the
// others on the GPU.
import * as THREE from 'three';

const FIRST_INSTANCES = 64;

export class GrowingInstances extends THREE.InstancedMesh {
    constructor(geometry, material, capacity) {
        super(geometry, material, 0);
        this.capacity = capacity;
    }

    // Room for the first `n` instances (at most the capacity), keeping those written: at least
    // twice the room held before, so that a list growing a slot at a time reallocates rarely.
    reserve(n) {
        n = Math.min(n, this.capacity);
        const held = this.instanceMatrix.count;
        if (n <= held) return;
        const room = Math.min(this.capacity, Math.max(n, 2 * held, FIRST_INSTANCES));
        const grown = new THREE.InstancedBufferAttribute(new Float32Array(16 * room), 16);
        grown.array.set(this.instanceMatrix.array);
        // Frees the old buffer on the GPU (three.js's renderer listens for it); the next draw
        // makes the new one.
        this.dispose();
        this.instanceMatrix = grown;
    }

    // Bytes held for the GPU.
    get bytes() {
        return this.instanceMatrix.array.byteLength;
    }

    // three.js tests a ray against the bounding sphere of the instances it first saw, computed
    // once: the lists change with every sort, so it is computed again for each pick.
    raycast(raycaster, intersects) {
        this.boundingSphere = null;
        super.raycast(raycaster, intersects);
    }
}
