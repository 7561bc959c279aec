// LOD4 to LOD2 of one terminal set: per shape, an InstancedMesh of the shape's unit-space mesh
// (LOD4) and, when the shape has an impostor, instanced impostor quads for LOD3 and LOD2. Each
// record becomes the instance matrix T·R·S of terminal_mesh.h: T its corner (cell-local), R
// from its quaternion (4 x snorm16), S = (w, h, d) with d = depthRatio · min(w, h) (flat shapes
// get a hair of depth so the matrix stays invertible for normals). With impostors, terminals
// are re-sorted into the three lists by lod_policy.classifyTerminal whenever the camera has
// moved or turned enough for the decision to change, or the LOD distances have changed,
// leaving out those behind their wall (a facade's; a tree's parts have none), outside the
// view or, with occlusion tiles, hidden behind the base volumes (a CPU stand-in for the
// native renderer's GPU pass); a sorted
// batch's LOD4 and coarse instance buffers grow with what the lists draw. Without impostors
// every terminal is LOD4 and the lists never change, unless a tree batch's cut
// moves trees between terminals and billboards, or a shape has a coarse mesh: its LOD4
// terminals are then sorted between the shape's mesh and the coarse one by
// lod_policy.coarseMeshReach, as the native pass does.
import * as THREE from 'three';

import { halfToFloat, quaternionAxes, snorm16ToFloat } from '../payload/record.js';
import { COARSE, classifyTerminal, coarseMeshReach, movedEnough, moveTolerance, OCCLUDED, turnedEnough } from '../stream/lod_policy.js';
import { GrowingInstances } from './growing_instances.js';

const FLAT_DEPTH = 1e-3;

// The records of a list's slots grown to hold `slot` (at least doubling, up to the run's
// `count`): a new slot holds none, so it is written.
function grownRecords(records, slot, count) {
    const grown = new Uint32Array(Math.min(count, Math.max(slot + 1, 2 * records.length, 64))).fill(0xffffffff);
    grown.set(records);
    return grown;
}

// Terminal i's instance matrix T·R·S into out[o .. o + 16), from its frame (corner, axes,
// depth) and size: derived where it is written, so that a batch keeps no matrix per terminal.
function writeMatrix(out, o, frames, sizes, i) {
    const f = frames, k = 13 * i, w = sizes[2 * i], h = sizes[2 * i + 1], depth = f[k + 12];
    const d = depth > 0 ? depth : FLAT_DEPTH * Math.max(Math.min(w, h), 1e-3);
    out[o] = f[k + 3] * w; out[o + 1] = f[k + 4] * w; out[o + 2] = f[k + 5] * w; out[o + 3] = 0;
    out[o + 4] = f[k + 6] * h; out[o + 5] = f[k + 7] * h; out[o + 6] = f[k + 8] * h; out[o + 7] = 0;
    out[o + 8] = f[k + 9] * d; out[o + 9] = f[k + 10] * d; out[o + 10] = f[k + 11] * d; out[o + 11] = 0;
    out[o + 12] = f[k]; out[o + 13] = f[k + 1]; out[o + 14] = f[k + 2]; out[o + 15] = 1;
}

// An unsorted batch's LOD4 list: every terminal of the run, once.
function fill(list, frames, sizes, first, count) {
    list.reserve(count);
    for (let i = 0; i < count; ++i) writeMatrix(list.instanceMatrix.array, 16 * i, frames, sizes, first + i);
    list.instanceMatrix.needsUpdate = true;
    list.count = count;
}

export class TerminalBatch {
    // `impostors`: an ImpostorSet (impostors.js) or null. `treeCut`: a tree batch, whose
    // terminals of trees shown as billboards updateLod leaves out. `freeStanding`: a tree
    // batch, whose parts no wall hides from behind (they are not backface culled).
    // The set's records are read here and not kept: `set` becomes its cell, grammar and count,
    // `buildings` each terminal's building id.
    constructor(set, library, material, impostors, { treeCut = false, freeStanding = treeCut } = {}) {
        this.set = { cell: set.cell, grammar: set.grammar, count: set.count };
        this.group = new THREE.Group();
        this.group.name = `terminals ${set.cell.q},${set.cell.r}/${set.grammar}`;
        const n = set.count;
        this.frames = new Float32Array(13 * n); // corner xyz, axes (9), depth: for the LOD decision
        this.sizes = new Float32Array(2 * n);
        this.buildings = new Uint32Array(n);
        const q = [0, 0, 0, 0], axes = new Float64Array(9);
        const w = set.records, p = set.positions;
        for (let i = 0; i < n; ++i) {
            const b = 8 * i;
            q[0] = snorm16ToFloat(w[b + 4] & 0xffff);
            q[1] = snorm16ToFloat(w[b + 4] >>> 16);
            q[2] = snorm16ToFloat(w[b + 5] & 0xffff);
            q[3] = snorm16ToFloat(w[b + 5] >>> 16);
            quaternionAxes(q, axes);
            const width = halfToFloat(w[b + 6] & 0xffff), height = halfToFloat(w[b + 6] >>> 16);
            const depth = halfToFloat(w[b + 7] >>> 16) * Math.min(width, height);
            const f = this.frames, k = 13 * i;
            f[k] = p[b]; f[k + 1] = p[b + 1]; f[k + 2] = p[b + 2];
            for (let j = 0; j < 9; ++j) f[k + 3 + j] = axes[j];
            f[k + 12] = depth;
            this.sizes[2 * i] = width;
            this.sizes[2 * i + 1] = height;
            this.buildings[i] = w[b + 3];
        }
        this.runs = [];
        let first = 0;
        for (let s = 0; s < set.countPerShape.length; ++s) {
            const count = set.countPerShape[s];
            if (count > 0) this.runs.push(this.makeRun(s, first, count, library, material, impostors));
            first += count;
        }
        this.counts = { 4: n, 3: 0, 2: 0, culled: 0, coarse: 0, occluded: 0 };
        this.lastCamera = null;
        this.lastOcclusion = null;
        this.lastForward = null;
        this.lastViewKey = null;
        this.lastDistances = null; // the LOD3, LOD2 and coarse distances of the last sort
        this.sorted = treeCut || this.runs.some((r) => r.lod3 || r.coarse);
        this.onWall = !freeStanding;
        this.lastCut = -1;
        // The building ids, and the frames and sizes kept to sort from; the lists' records and
        // instance buffers are counted as they grow (gpuBytes).
        this.baseBytes = this.buildings.byteLength + (this.sorted ? this.frames.byteLength + this.sizes.byteLength : 0);
        for (const run of this.runs) {
            if (!this.sorted) fill(run.lod4, this.frames, this.sizes, run.first, run.count);
            if (run.coarse) this.baseBytes += run.reach.byteLength;
        }
        // Without impostors or a tree cut the lists never change: the instance buffers hold all
        // there is. Sorted, each list grows with what it draws (updateLod), from nothing.
        if (!this.sorted) this.frames = this.sizes = null;
    }

    makeRun(shape, first, count, library, material, impostors) {
        const info = library.shape(shape);
        const lod4 = new GrowingInstances(info?.geometry ?? library.shapes[0]?.geometry, material, count);
        lod4.frustumCulled = false; // the cell's bounds decide visibility
        lod4.userData.batch = this;
        lod4.userData.records = null; // instance i is record first + i until re-sorted
        lod4.userData.first = first;
        this.group.add(lod4);
        // `slots`: per list, the record each of its slots holds (sorted batches).
        const run = { shape, first, count, lod4, lod3: null, lod2: null, coarse: null, slots: { 4: new Uint32Array(0) } };
        const atlas = impostors?.atlasOf(library.grammar.index, shape);
        if (atlas) {
            run.lod3 = impostors.makeMesh(atlas, 3, count);
            run.lod2 = impostors.makeMesh(atlas, 2, count);
            run.lod3.count = run.lod2.count = 0;
            for (const mesh of [run.lod3, run.lod2]) this.group.add(mesh);
            run.slots[3] = new Uint32Array(0);
            run.slots[2] = new Uint32Array(0);
        }
        if (info?.coarse) {
            // As in the native pass, a LOD4 terminal small enough on screen draws its shape's
            // coarse mesh, whether or not the shape has an impostor for farther away.
            run.coarse = new GrowingInstances(info.coarse.geometry, material, count);
            run.coarse.frustumCulled = false;
            run.coarse.userData.batch = this;
            run.slots[COARSE] = run.coarse.userData.records = new Uint32Array(0); // record of each coarse instance
            this.group.add(run.coarse);
            // Each terminal's coarseMeshReach per metre of deviation scale: its scope is fixed.
            run.reach = new Float32Array(count);
            for (let i = 0; i < count; ++i) {
                const r = first + i;
                run.reach[i] = coarseMeshReach(info.coarse.deviation, this.sizes[2 * r], this.sizes[2 * r + 1], this.frames[13 * r + 12], 1);
            }
        }
        return run;
    }

    // `camera`: the camera position relative to this batch's cell origin (doubles); `cut`: the
    // batch's TreeBillboards, whose billboard trees' terminals are left out, or null; `view`:
    // lod_policy's view, whose terminals outside it are left out too (null: none are);
    // `occlusion`: an OcclusionTiles, whose hidden terminals are left out, sorted again with
    // each new one (null: none are).
    updateLod(camera, distances, cut = null, view = null, occlusion = null) {
        if (!this.sorted) return; // (then the lists hold every terminal, and occlusion is not tested)
        const cutVersion = cut ? cut.version : -1;
        const viewKey = view ? view.key : null;
        const perMetre = distances.coarse ?? 0;
        // The distances change with the viewport's height and the profile, which the view's key
        // does not hold.
        const last = this.lastDistances;
        const sameDistances =
            last !== null && last[0] === distances.lod3 && last[1] === distances.lod2 && last[2] === perMetre;
        const occlusionVersion = occlusion ? occlusion.version : null;
        if (cutVersion === this.lastCut && viewKey === this.lastViewKey && sameDistances &&
            occlusionVersion === this.lastOcclusion && !movedEnough(this.lastCamera, camera, distances.lod3) &&
            !(view && turnedEnough(this.lastForward, view.forward)))
            return;
        this.lastOcclusion = occlusionVersion;
        this.lastCamera = camera.slice();
        this.lastCut = cutVersion;
        this.lastDistances = [distances.lod3, distances.lod2, perMetre];
        this.lastViewKey = viewKey;
        this.lastForward = view ? view.forward.slice() : null;
        // How far the camera may move before the lists are sorted again.
        const slack = moveTolerance(distances.lod3);
        const counts = { 4: 0, 3: 0, 2: 0, culled: 0, coarse: 0, occluded: 0 };
        const corner = [0, 0, 0], axes = new Float64Array(9);
        for (const run of this.runs) {
            const lists = { 4: run.lod4, 3: run.lod3, 2: run.lod2, [COARSE]: run.coarse };
            const records = run.slots;
            const filled = { 4: 0, 3: 0, 2: 0, [COARSE]: 0 };
            const changed = { 4: false, 3: false, 2: false, [COARSE]: false };
            for (let i = run.first; i < run.first + run.count; ++i) {
                if (cut && cut.isFar(this.buildings[i])) continue;
                const f = this.frames, k = 13 * i;
                corner[0] = f[k] - camera[0];
                corner[1] = f[k + 1] - camera[1];
                corner[2] = f[k + 2] - camera[2];
                for (let j = 0; j < 9; ++j) axes[j] = f[k + 3 + j];
                const reach = run.coarse ? run.reach[i - run.first] * perMetre : Infinity;
                const lod = classifyTerminal(corner, axes, this.sizes[2 * i], this.sizes[2 * i + 1], f[k + 12], distances, !!run.lod3, view, slack, reach, occlusion, this.onWall);
                if (lod === 0 || lod === OCCLUDED) {
                    ++counts[lod === 0 ? 'culled' : 'occluded'];
                    continue;
                }
                // A list slot that holds the same record as after the last sort holds its matrix
                // already, on the GPU too: only lists with a changed slot are uploaded again.
                const slot = filled[lod]++;
                if (slot >= records[lod].length) records[lod] = grownRecords(records[lod], slot, run.count);
                if (records[lod][slot] !== i) {
                    records[lod][slot] = i;
                    lists[lod].reserve(slot + 1); // instance buffers and impostor quads grow as they fill
                    writeMatrix(lists[lod].instanceMatrix.array, 16 * slot, this.frames, this.sizes, i);
                    changed[lod] = true;
                }
                ++counts[lod === COARSE ? 4 : lod];
                if (lod === COARSE) ++counts.coarse;
            }
            for (const lod of [4, 3, 2, COARSE]) {
                if (!lists[lod]) continue; // a shape without impostor has no LOD3 and LOD2 lists
                lists[lod].count = filled[lod];
                if (changed[lod]) lists[lod].instanceMatrix.needsUpdate = true;
            }
            run.lod4.userData.records = records[4];
            if (run.coarse) run.coarse.userData.records = records[COARSE];
        }
        this.counts = counts;
    }

    // Bytes for the GPU: what the batch keeps, and the instance buffers, impostor quads and
    // lists' records, which grow with the most instances a list has drawn.
    get gpuBytes() {
        let bytes = this.baseBytes;
        for (const run of this.runs) {
            for (const list of [run.lod4, run.coarse, run.lod3, run.lod2]) bytes += list?.bytes ?? 0;
            for (const records of Object.values(run.slots)) bytes += records.byteLength;
        }
        return bytes;
    }

    // The record index behind instance `instanceId` of a LOD4 mesh of this batch.
    recordOf(mesh, instanceId) {
        const records = mesh.userData.records;
        return records ? records[instanceId] : mesh.userData.first + instanceId;
    }

    dispose() {
        for (const run of this.runs) for (const mesh of [run.lod4, run.lod3, run.lod2, run.coarse]) mesh?.dispose();
    }
}
