// The billboards of one tree batch, from its extruded set: each tree stands at the centre of
// its footprint on its base elevation (as lod/tree_pass.cpp places it) and is drawn with the
// impostor of its species, found by its exact parameter values. Per tree, as the native tree
// cut: a tree nearer the camera than the terminal distance is drawn from the batch's terminals
// (`isBillboard` false: TerminalBatch shows its terminals), a farther one as its billboard. A
// tree whose values match no served species (it was edited, and the service has not baked its
// species yet) is never a billboard: `unmatched` counts them, and the streamer then draws the
// batch's terminals at any distance, until a new species makes it rebuild the billboards.
import * as THREE from 'three';

import { movedEnough } from '../stream/lod_policy.js';

export class TreeBillboards {
    // `set`: a decoded extruded set of a tree grammar; `species`: a TreeImpostors.
    constructor(set, species) {
        this.group = new THREE.Group();
        this.group.name = `trees ${set.cell.q},${set.cell.r}/${set.grammar}`;
        const { buildings, footprints } = set;
        const n = buildings.count;
        const values = new Float32Array(set.parametersPerBuilding);
        this.bases = new Float32Array(3 * n);
        this.speciesOfTree = new Int32Array(n);
        this.unmatched = 0;
        this.generation = species.generation; // the species known when the trees were matched
        const perSpecies = new Map(); // species index -> trees
        for (let i = 0; i < n; ++i) {
            for (let j = 0; j < values.length; ++j) values[j] = set.parameters[j][i];
            const s = species.speciesOf(set.grammar, values);
            this.speciesOfTree[i] = s;
            let x = 0, y = 0;
            const first = buildings.firstVertex[i], count = buildings.vertexCount[i];
            for (let v = first; v < first + count; ++v) {
                x += footprints.x[v];
                y += footprints.y[v];
            }
            this.bases.set([x / Math.max(count, 1), y / Math.max(count, 1), buildings.baseElevation[i]], 3 * i);
            if (s < 0) ++this.unmatched;
            else perSpecies.set(s, (perSpecies.get(s) ?? 0) + 1);
        }
        this.treeIds = buildings.id;
        this.meshes = new Map(); // species index -> TreeQuads, `count` the billboards drawn
        this.spheres = new Map(); // species index -> its bounding sphere (tree space): x, y, z, radius
        for (const [s, capacity] of perSpecies) {
            const mesh = species.makeMesh(s, capacity);
            this.meshes.set(s, mesh);
            this.group.add(mesh);
            const { centre, radius } = species.species[s].impostor;
            this.spheres.set(s, [...centre, radius]);
        }
        this.billboardIds = new Set(); // the trees drawn as billboards now
        this.count = 0; // billboards drawn
        this.occluded = 0; // billboards the occlusion tiles hide
        this.version = 0; // grows whenever the cut changes
        this.lastCamera = null;
        this.lastDistance = -1;
        this.lastOcclusion = null;
        // The billboards' vertices, and the bases and species the cut reads.
        this.gpuBytes = this.bases.byteLength + this.speciesOfTree.byteLength;
        for (const mesh of this.meshes.values()) this.gpuBytes += mesh.bytes;
    }

    isBillboard(treeId) {
        return this.billboardIds.has(treeId);
    }

    // The cut for a camera at `camera` (cell-local): trees of a served species at least
    // `distance` from it are billboards (distance 0: all of them). Recomputed when the camera
    // has moved enough for a tree to cross, the distance changed, or with a new `occlusion`
    // (an OcclusionTiles, or null), whose hidden billboards are not drawn: they stay billboards
    // for the cut, so their terminals are not drawn either.
    updateCut(camera, distance, occlusion = null) {
        const occlusionVersion = occlusion ? occlusion.version : null;
        if (occlusionVersion === this.lastOcclusion) {
            if (this.lastCamera && distance === 0 && this.lastDistance === 0) return; // all, wherever the camera is
            if (distance === this.lastDistance && !movedEnough(this.lastCamera, camera, distance)) return;
        }
        this.lastOcclusion = occlusionVersion;
        this.lastCamera = camera.slice();
        this.lastDistance = distance;
        this.occluded = 0;
        let changed = false;
        const filled = new Map();
        const b = this.bases;
        for (let i = 0; i < this.speciesOfTree.length; ++i) {
            const s = this.speciesOfTree[i];
            const far = s >= 0 && Math.hypot(b[3 * i] - camera[0], b[3 * i + 1] - camera[1], b[3 * i + 2] - camera[2]) >= distance;
            const id = this.treeIds[i];
            if (far !== this.billboardIds.has(id)) {
                changed = true;
                if (far) this.billboardIds.add(id);
                else this.billboardIds.delete(id);
            }
            if (!far) continue;
            if (occlusion) {
                const sphere = this.spheres.get(s), k = 3 * i;
                const [x, y, z] = [b[k] + sphere[0] - camera[0], b[k + 1] + sphere[1] - camera[1], b[k + 2] + sphere[2] - camera[2]];
                if (occlusion.hidesSphere(x, y, z, sphere[3])) {
                    ++this.occluded;
                    continue;
                }
            }
            const slot = filled.get(s) ?? 0;
            this.meshes.get(s).place(slot, b, 3 * i);
            filled.set(s, slot + 1);
        }
        this.count = 0;
        for (const [s, mesh] of this.meshes) {
            mesh.show(filled.get(s) ?? 0);
            this.count += mesh.count;
        }
        if (changed) ++this.version;
    }

    dispose() {
        for (const mesh of this.meshes.values()) mesh.dispose();
    }
}
