// The far forms of one tree batch, from its extruded set: each tree stands at the centre of
// its footprint on its base elevation (as lod/tree_pass.cpp places it) and is drawn with the
// impostor of its species, found by its exact parameter values. Per tree, as the native tree
// cut: a tree nearer the camera than the terminal distance is drawn from the batch's terminals
// (`isFar` false: TerminalBatch shows its terminals), a farther one as its billboard, or as a
// point (tree_points.js) where it is too small on screen for its billboard to show more than
// an average colour and its species has view averages. A tree whose values match no served
// species (it was edited, and the service has not baked its species yet) is never far:
// `unmatched` counts them, and the streamer then draws the batch's terminals at any distance,
// until a new species makes it rebuild the billboards.
import * as THREE from 'three';

import { moveTolerance } from '../stream/lod_policy.js';
import { treeIsPoint } from './tree_points.js';

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
        this.pointSpecies = new Set([...perSpecies.keys()].filter((s) => species.hasPoints(s)));
        let pointTrees = 0; // trees whose species can be drawn as points
        for (const s of this.pointSpecies) pointTrees += perSpecies.get(s);
        this.points = pointTrees > 0 ? species.makePoints(pointTrees) : null;
        if (this.points) this.group.add(this.points);
        // The smallest sphere of a species drawn as points: the nearest point threshold.
        this.smallestRadius = Math.min(...[...this.pointSpecies].map((s) => this.spheres.get(s)[3]));
        this.farIds = new Set(); // the trees drawn far, as billboards or points, now
        this.count = 0; // billboards drawn
        this.pointCount = 0; // points drawn
        this.occluded = 0; // far trees the occlusion tiles hide
        this.version = 0; // grows whenever the cut changes
        this.lastCamera = null;
        this.lastDistance = -1;
        this.lastPointScale = -1;
        this.lastOcclusion = null;
        this.margin = 0; // how far the camera may move from lastCamera before a tree changes form
        // The billboards' and points' vertices, and the bases and species the cut reads.
        this.gpuBytes = this.bases.byteLength + this.speciesOfTree.byteLength + (this.points?.bytes ?? 0);
        for (const mesh of this.meshes.values()) this.gpuBytes += mesh.bytes;
    }

    isFar(treeId) {
        return this.farIds.has(treeId);
    }

    // The cut for a camera at `camera` (cell-local): trees of a served species at least
    // `distance` from it are far (distance 0: all of them), and a far tree is a point where
    // treeIsPoint says so for `pointScale` (tree_points.pointDistancePerMetre; 0: no points),
    // a billboard otherwise. Recomputed when the camera has moved enough for a tree to change
    // form (by the margin the last cut left, and at least moveTolerance of the nearest
    // threshold, so that a hovering camera re-decides nothing), the distance or point scale
    // changed, or with a new `occlusion` (an OcclusionTiles, or null), whose hidden far trees
    // are not drawn: they stay far for the cut, so their terminals are not drawn either.
    updateCut(camera, distance, occlusion = null, pointScale = 0) {
        const occlusionVersion = occlusion ? occlusion.version : null;
        const scale = this.points ? pointScale : 0;
        if (this.lastCamera && occlusionVersion === this.lastOcclusion && distance === this.lastDistance && scale === this.lastPointScale) {
            const c = this.lastCamera;
            const threshold = Math.min(distance > 0 ? distance : Infinity, scale > 0 ? 2 * this.smallestRadius * scale : Infinity);
            if (Math.hypot(camera[0] - c[0], camera[1] - c[1], camera[2] - c[2]) < Math.max(this.margin, moveTolerance(threshold))) return;
        }
        this.lastOcclusion = occlusionVersion;
        this.lastCamera = camera.slice();
        this.lastDistance = distance;
        this.lastPointScale = scale;
        this.occluded = 0;
        let changed = false, margin = Infinity, points = 0;
        const filled = new Map();
        const b = this.bases;
        for (let i = 0; i < this.speciesOfTree.length; ++i) {
            const s = this.speciesOfTree[i];
            if (s < 0) continue;
            const k = 3 * i;
            const fromBase = Math.hypot(b[k] - camera[0], b[k + 1] - camera[1], b[k + 2] - camera[2]);
            const far = fromBase >= distance;
            if (distance > 0) margin = Math.min(margin, Math.abs(fromBase - distance));
            const id = this.treeIds[i];
            if (far !== this.farIds.has(id)) {
                changed = true;
                if (far) this.farIds.add(id);
                else this.farIds.delete(id);
            }
            if (!far) continue;
            const sphere = this.spheres.get(s);
            const [x, y, z] = [b[k] + sphere[0] - camera[0], b[k + 1] + sphere[1] - camera[1], b[k + 2] + sphere[2] - camera[2]];
            let point = false;
            if (scale > 0 && this.pointSpecies.has(s)) {
                const fromCentre = Math.hypot(x, y, z);
                margin = Math.min(margin, Math.abs(fromCentre - 2 * sphere[3] * scale));
                point = treeIsPoint(sphere[3], fromCentre, scale);
            }
            if (occlusion && occlusion.hidesSphere(x, y, z, sphere[3])) {
                ++this.occluded;
                continue;
            }
            if (point) {
                this.points.place(points++, b[k] + sphere[0], b[k + 1] + sphere[1], b[k + 2] + sphere[2], s);
                continue;
            }
            const slot = filled.get(s) ?? 0;
            this.meshes.get(s).place(slot, b, k);
            filled.set(s, slot + 1);
        }
        this.margin = margin;
        this.count = 0;
        for (const [s, mesh] of this.meshes) {
            mesh.show(filled.get(s) ?? 0);
            this.count += mesh.count;
        }
        this.points?.show(points);
        this.pointCount = points;
        if (changed) ++this.version;
    }

    dispose() {
        for (const mesh of this.meshes.values()) mesh.dispose();
        this.points?.dispose();
    }
}
