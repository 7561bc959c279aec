// Per cell, what to fetch and what to draw (the browser's counterpart of cells::Scheduler):
// every update the LOD policy decides each cell's LOD from the camera; cells in view (and those
// within a cell's size of the camera) want their batches' extruded sets (LOD0) and, in terminal
// cells, their terminal sets; the fetch queue gets them highest priority first (extruded sets
// of cells in view, then terminal sets by screen-space error) and drops what is no longer
// wanted. Until a wanted payload arrives a batch keeps drawing what it drew before (the old
// version after an edit, the extruded set before its terminals), so nothing leaves a hole.
// Decoded payloads and their GPU objects live in a byte-budgeted LRU, and a view that wants more
// terminal sets than the budget holds draws the lowest-priority ones' batches at LOD0, their
// trees as billboards (terminal_budget.js).
import * as THREE from 'three';

import { getBinary } from '../api.js';
import { decodeExtrudedSet } from '../payload/extruded_set.js';
import { decodeTerminalSet } from '../payload/terminal_set.js';
import { buildBuildingPoints, farAsPoints, largestBuildingDiagonal } from '../render/building_points.js';
import { buildExtrudedGeometry } from '../render/extruded_mesh.js';
import { geometryBytes } from '../render/geometry_bytes.js';
import { OCCLUDER_LAYER } from '../render/occluder_depth.js';
import { TerminalBatch } from '../render/terminal_batch.js';
import { TreeBillboards } from '../render/tree_billboards.js';
import { pointDistancePerMetre } from '../render/tree_points.js';
import { ContentCache } from './content_cache.js';
import { FetchQueue } from './fetch_queue.js';
import { decideCell, EXTRUDED, lodDistance, screenScale, TERMINALS, terminalLodDistances } from './lod_policy.js';
import { admitTerminalSets, bytesPerMember } from './terminal_budget.js';

const BACKING_INSET = 0.5; // metres: base volumes behind terminal facades, as the native renderer

// A terminal set's fetch priority, which is also its rank for the budget: in view first, then
// by its cell's screen-space error (capped at 1e6); extruded sets go before either.
const terminalPriority = (visible, sse) => (visible ? 2e6 : 0) + sse;
const extrudedPriority = (visible, sse) => (visible ? 3e6 : 1e6) + sse;

// Whether a cell group's object is a base volume, which the occlusion image draws.
const isOccluder = (object) => object.layers.isEnabled(OCCLUDER_LAYER);

export class Streamer {
    // `occluders`: an OccluderDepth (render/occluder_depth.js) to cull the terminals that the
    // base volumes hide, or null.
    constructor({ scene, world, libraries, impostors, trees, treeForm = 'auto', materials, budgetBytes, concurrency, onError, onStale, occluders = null }) {
        this.scene = scene;
        this.profile = scene.lod;
        this.world = world;
        this.libraries = libraries; // per grammar index: ShapeLibrary
        this.impostors = impostors;
        this.trees = trees; // TreeImpostors: species billboards and points
        this.treeForm = treeForm; // 'auto' (by distance), every tree as 'terminals' or 'billboards', or 'none'
        this.materials = materials; // {extruded, backing, terminal, points (null: far buildings keep their shells)}
        this.occluders = occluders;
        this.occluderVersion = 0; // changes whenever the base volumes the cells draw change
        this.onError = onError;
        this.cells = [];
        this.lodOf = new Map(); // "q,r" -> LOD, kept across index reloads
        this.cache = new ContentCache(budgetBytes, (value) => this.dispose(value));
        this.queue = new FetchQueue({
            concurrency,
            load: (request, signal) => this.load(request, signal),
            onLoaded: (request, value) => this.cache.put(request.url, value, value.set.byteSize),
            onFailed: (request, error) => onError(`${request.url}: ${error.message ?? error}`),
            onStale: () => onStale(),
        });
        this.stats = { visible: 0, cells: { extruded: 0, terminals: 0, held: 0 }, pointBatches: 0, terminals: { 4: 0, 3: 0, 2: 0, coarse: 0, occluded: 0 }, trees: { billboards: 0, points: 0, terminals: 0, edited: 0, occluded: 0 }, decodeMs: 0 };
        this.budget = { room: 0, wanted: 0, admitted: 0 }; // the latest admitTerminals
        // Terminal sets' bytes as last cached, kept after they are evicted, so that a set that
        // did not fit is not fetched again: with its GPU objects (built), or, for one never
        // drawn, its decoded records alone, a lower bound that still tells it does not fit.
        this.measured = new Map(); // url -> {grammar, members, bytes, built}
        this.frustum = new THREE.Frustum();
        this.box = new THREE.Box3();
    }

    setIndex(index) {
        this.cells = index.cells.map((c) => ({
            ...c,
            id: `${c.q},${c.r}`,
            batches: c.batches.map((b) => ({ ...b, shown: { extruded: null, terminal: null } })),
        }));
        this.seq = index.seq;
    }

    // Whether every batch of `changed` that this viewer draws in view is drawn at its new
    // version or a later one; null when none of them is in view. (A cell out of view keeps the
    // `drawn` of its last frame in view.)
    drawsVersions(changed) {
        let drawn = 0;
        for (const c of changed) {
            const { cell, batch } = this.batchOf(c);
            if (!batch?.drawn || !this.world.cellGroup(cell).visible) continue;
            if (batch.drawn.version < c.version) return false;
            ++drawn;
        }
        return drawn > 0 ? true : null;
    }

    // Whether any payload that `changed` names is being fetched.
    fetchesAnyOf(changed) {
        return changed.some((c) => this.queue.running.has(c.terminal_set) || this.queue.running.has(c.extruded_set));
    }

    // The cell and batch an entry of a `changed` list names (either undefined when unknown).
    batchOf(change) {
        const cell = this.cells.find((x) => x.q === change.cell[0] && x.r === change.cell[1]);
        return { cell, batch: cell?.batches.find((b) => b.grammar === change.grammar) };
    }

    // The `changed` list of an edit reply or event: new keys, versions and URLs per batch.
    applyChanged(changed) {
        for (const c of changed) {
            const { batch } = this.batchOf(c);
            if (!batch || batch.version >= c.version) continue;
            Object.assign(batch, { key: c.key, version: c.version, terminal_set: c.terminal_set, extruded_set: c.extruded_set });
        }
    }

    async load(request, signal) {
        const { bytes, version } = await getBinary(request.url, { signal });
        const start = performance.now();
        const set = request.kind === 'terminal' ? decodeTerminalSet(bytes) : decodeExtrudedSet(bytes, { elements: false });
        this.stats.decodeMs += performance.now() - start;
        return { kind: request.kind, set, version, grammar: request.grammar, members: request.members, wire: bytes.byteLength };
    }

    dispose(value) {
        value.terminals?.dispose();
        value.billboards?.dispose();
        value.lod0?.geometry.dispose();
        value.backing?.geometry.dispose();
        value.points?.geometry.dispose();
    }

    grammar(index) {
        return this.scene.grammars.find((g) => g.index === index);
    }

    // Builds (once) and returns the object a content entry is drawn with.
    object(url, value, variant) {
        if (value.kind === 'extruded' && variant === 'billboards') {
            const old = value.billboards;
            // Trees that matched no species are matched again once a species was added.
            if (!old || (old.unmatched > 0 && old.generation !== this.trees.generation)) {
                value.billboards = new TreeBillboards(value.set, this.trees);
                this.cache.grow(url, value.billboards.gpuBytes - (old?.gpuBytes ?? 0));
                old?.dispose();
            }
            return value.billboards.group;
        }
        if (value.kind === 'extruded' && variant === 'points') {
            if (!value.points) {
                value.points = buildBuildingPoints(value.set, this.grammar(value.set.grammar), this.materials.points);
                this.cache.grow(url, geometryBytes(value.points.geometry));
            }
            return value.points;
        }
        if (value.kind === 'extruded') {
            if (!value[variant]) {
                const inset = variant === 'backing' ? BACKING_INSET : 0;
                const { geometry, buildingOfTriangle } = buildExtrudedGeometry(value.set, this.grammar(value.set.grammar), { inset, windows: variant === 'lod0' });
                const mesh = new THREE.Mesh(geometry, variant === 'lod0' ? this.materials.extruded : this.materials.backing);
                mesh.layers.enable(OCCLUDER_LAYER); // opaque: what it hides need not be drawn
                mesh.userData = { buildingOfTriangle, grammar: value.set.grammar, version: value.version, kind: 'extruded' };
                value[variant] = mesh;
                this.cache.grow(url, geometryBytes(geometry) + buildingOfTriangle.byteLength);
            }
            return value[variant];
        }
        if (!value.terminals) {
            const library = this.libraries[value.set.grammar];
            const trees = this.grammar(value.set.grammar)?.kind === 'tree';
            const treeCut = this.trees.enabled && trees;
            value.terminals = new TerminalBatch(value.set, library, this.materials.terminal, this.impostors.enabled ? this.impostors : null, { treeCut, freeStanding: trees });
            // The batch keeps what it sorts and draws from; the decoded records go.
            const decoded = value.set.byteSize;
            value.set = value.terminals.set;
            this.cache.grow(url, value.terminals.gpuBytes - decoded);
        }
        return value.terminals.group;
    }

    // `view`: {position, forward, fovY, viewportHeight}; `camera`: the three.js camera at the origin.
    update(view, camera) {
        camera.updateMatrixWorld();
        this.frustum.setFromProjectionMatrix(new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse));
        const distances = terminalLodDistances(this.profile, view);
        // The view the terminal lists are sorted for (lod_policy.outsideView): terminals outside
        // it are not drawn at all, so they cost no vertex work, which a software rasteriser pays
        // in full for every quad and instance it clips away.
        const f = view.forward, length = Math.hypot(f[0], f[1], f[2]) || 1;
        const terminalView = {
            sides: this.frustum.planes.slice(0, 4).map((plane) => ({ normal: plane.normal.toArray(), constant: plane.constant })),
            forward: [f[0] / length, f[1] / length, f[2] / length],
            key: `${camera.fov} ${camera.aspect}`,
        };
        // Trees are terminals only near the camera: beyond the distance at which the profile's
        // tree error stays under the budget they are billboards of their species' impostor
        // (updateTrees). As in the native renderer, a tree error of 0 keeps every tree of a
        // terminal-set cell geometry (extruded cells still draw theirs as billboards).
        const treeError = this.profile.tree_geometric_error;
        const treeDistance = treeError > 0 ? lodDistance(treeError, this.profile, view.fovY, view.viewportHeight) : Infinity;
        const scale = screenScale(view.viewportHeight, view.fovY);
        const pixelScale = scale * this.world.renderer.getPixelRatio();
        if (this.materials.points) this.materials.points.uniforms.screenScale.value = pixelScale;
        if (this.trees.pointMaterial) this.trees.pointMaterial.uniforms.screenScale.value = pixelScale;
        const treePoints = pointDistancePerMetre(scale, this.profile.max_screen_space_error);
        const requests = [];
        const pinned = new Set();
        const stats = { visible: 0, cells: { extruded: 0, terminals: 0, held: 0 }, pointBatches: 0, terminals: { 4: 0, 3: 0, 2: 0, coarse: 0, occluded: 0 }, trees: { billboards: 0, points: 0, terminals: 0, edited: 0, occluded: 0 } };
        // The base volumes the last update left in the cell groups, seen from this view.
        const occlusion = this.occluders ? this.occluders.update(view, this.occluderVersion) : null;
        const p = view.position;
        const wanted = []; // the cells this update draws or fetches for: {cell, decision, visible, sse}
        for (const cell of this.cells) {
            const decision = decideCell(this.lodOf.get(cell.id), cell.bounds, view, this.profile);
            this.lodOf.set(cell.id, decision.lod);
            cell.lod = decision.lod;
            cell.distance = decision.distance;
            this.box.min.set(cell.bounds.min[0] - p[0], cell.bounds.min[1] - p[1], cell.bounds.min[2] - p[2]);
            this.box.max.set(cell.bounds.max[0] - p[0], cell.bounds.max[1] - p[1], cell.bounds.max[2] - p[2]);
            const visible = this.frustum.intersectsBox(this.box);
            const near = decision.distance < this.scene.cell_size;
            const group = this.world.cellGroup(cell);
            if (group.visible !== visible && group.children.some(isOccluder)) ++this.occluderVersion;
            group.visible = visible;
            if (visible || near) wanted.push({ cell, decision, visible, sse: Math.min(decision.sse, 1e6) });
        }
        const heldBack = this.admitTerminals(wanted, treeDistance);
        for (const { cell, decision, visible, sse } of wanted) {
            const group = this.world.cellGroup(cell);
            const held = cell.batches.some((b) => heldBack.has(b.terminal_set));
            if (visible) {
                ++stats.visible;
                ++stats.cells[decision.lod];
                if (held) ++stats.cells.held;
            }
            const objects = [];
            const local = [p[0] - cell.origin[0], p[1] - cell.origin[1], p[2] - cell.origin[2]]; // the camera, cell-local
            const frame = { cell, visible, sse, distances, local, stats, objects, pinned, requests, view: terminalView, occlusion, heldBack, treePoints };
            for (const b of cell.batches) {
                if (this.grammar(b.grammar)?.kind === 'tree') {
                    this.updateTrees(b, decision, treeDistance, frame);
                    continue;
                }
                // A batch whose terminal set the budget holds back draws as an extruded cell's.
                const lod = heldBack.has(b.terminal_set) ? EXTRUDED : decision.lod;
                const wantTerminals = lod === TERMINALS;
                this.request(b, 'extruded', frame);
                if (wantTerminals) this.request(b, 'terminal', frame);
                const ext = this.pick(b.extruded_set, b.shown.extruded);
                let term = wantTerminals || lod === EXTRUDED ? this.pickTerminals(b) : null;
                if (lod === EXTRUDED && ext) term = null; // LOD0 is enough here
                b.shown = { extruded: ext, terminal: term };
                if (term) this.showTerminals(b, term, frame);
                if (ext) {
                    const variant = term ? 'backing' : this.lod0Form(ext, decision.distance, view);
                    if (visible && variant === 'points') ++stats.pointBatches;
                    objects.push(this.object(ext, this.cache.get(ext), variant));
                    pinned.add(ext);
                    if (!term) b.drawn = { url: ext, version: this.cache.get(ext).version, kind: 'extruded' };
                }
                if (!term && !ext) b.drawn = null;
            }
            const keep = new Set(objects);
            for (const child of [...group.children]) {
                if (keep.has(child)) continue;
                group.remove(child);
                if (isOccluder(child)) ++this.occluderVersion;
            }
            for (const o of objects) {
                if (o.parent === group) continue;
                group.add(o);
                if (isOccluder(o)) ++this.occluderVersion;
            }
        }
        // Cells neither visible nor near draw nothing and pin nothing.
        for (const cell of this.cells) {
            if (!this.world.cellGroup(cell).visible && cell.distance >= this.scene.cell_size) this.world.cellGroup(cell).clear();
        }
        this.queue.want(requests);
        this.cache.trim(pinned);
        Object.assign(this.stats, stats);
    }

    // How an extruded batch drawn at LOD0 is drawn from `distance` metres (its cell's nearest):
    // 'points' where every one of its buildings is under the point size (building_points.js),
    // else 'lod0', the shells.
    lod0Form(url, distance, view) {
        if (!this.materials.points) return 'lod0';
        const value = this.cache.get(url);
        value.largestDiagonal ??= largestBuildingDiagonal(value.set);
        return farAsPoints(value.largestDiagonal, distance, view, this.profile) ? 'points' : 'lod0';
    }

    // The terminal sets this update wants but the budget holds back (terminal_budget.js): the
    // candidates are those of building batches in terminal cells and of tree batches near
    // enough for terminals (treesNear) whose trees billboards can stand for, admitted highest
    // priority first within the budget less the cached bytes of what every frame pins
    // regardless (the batches' extruded sets, and the other tree batches' terminals: edited
    // trees whose species is not baked yet, or every near tree without species impostors).
    admitTerminals(wanted, treeDistance) {
        this.measure();
        const perMember = bytesPerMember([...this.measured.values()].filter((m) => m.built));
        const candidates = [];
        let pinnedAnyway = 0;
        const billboards = this.treesAsBillboards();
        for (const { cell, decision, visible, sse } of wanted)
            for (const b of cell.batches) {
                pinnedAnyway += this.cache.bytesOf(this.pick(b.extruded_set, b.shown.extruded));
                const trees = this.grammar(b.grammar)?.kind === 'tree';
                const candidate = trees ? billboards && this.treesNear(decision, treeDistance) : decision.lod === TERMINALS;
                if (!candidate) {
                    if (trees) pinnedAnyway += this.cache.bytesOf(b.shown.terminal);
                    continue;
                }
                const url = b.terminal_set;
                const bytes = this.measured.get(url)?.bytes ?? Math.max(this.cache.bytesOf(url), perMember(b.grammar) * b.members);
                candidates.push({ url, priority: terminalPriority(visible, sse), bytes, drawn: b.shown.terminal === url });
            }
        const room = Math.max(this.cache.budget - pinnedAnyway, 0);
        const admitted = admitTerminalSets(candidates, room);
        this.budget = { room, wanted: candidates.length, admitted: admitted.size };
        return new Set(candidates.filter((c) => !admitted.has(c.url)).map((c) => c.url));
    }

    // Whether trees can be drawn as their species' billboards (served, and not turned off).
    treesAsBillboards() {
        return this.trees.enabled && this.treeForm !== 'terminals';
    }

    // Whether a tree batch's trees near the camera are drawn from its terminals (updateTrees).
    treesNear(decision, treeDistance) {
        return this.treeForm === 'terminals' || (this.treeForm !== 'billboards' && decision.lod === TERMINALS && decision.distance < treeDistance);
    }

    // Records the bytes of the cached terminal sets (measured).
    measure() {
        for (const { url, value, bytes } of this.cache.list()) {
            if (value.kind !== 'terminal') continue;
            const built = !!value.terminals, before = this.measured.get(url);
            if (!built && before?.built) continue;
            this.measured.set(url, { grammar: value.grammar, members: value.members, bytes, built });
        }
    }

    pick(url, old) {
        return this.cache.has(url) ? url : old && this.cache.has(old) ? old : null;
    }

    // The terminal set to draw for batch `b` (the wanted one, else the one drawn before), once
    // its shapes and impostors are loaded.
    pickTerminals(b) {
        const term = this.pick(b.terminal_set, b.shown.terminal);
        return term && this.libraries[b.grammar]?.isReady && this.impostors.isReady ? term : null;
    }

    request(b, kind, frame) {
        const url = kind === 'terminal' ? b.terminal_set : b.extruded_set;
        if (this.cache.has(url)) return;
        const priority = (kind === 'terminal' ? terminalPriority : extrudedPriority)(frame.visible, frame.sse);
        frame.requests.push({ url, kind, grammar: b.grammar, members: b.members, priority });
    }

    // `cut`: a tree batch's TreeBillboards, whose billboard trees' terminals are not drawn.
    showTerminals(b, term, frame, cut = null) {
        const value = this.cache.get(term);
        frame.objects.push(this.object(term, value, 'terminals'));
        const bytes = value.terminals.gpuBytes;
        value.terminals.updateLod(frame.local, frame.distances, cut, frame.view, frame.occlusion);
        // Impostor quads grow with what they draw.
        if (value.terminals.gpuBytes !== bytes) this.cache.grow(term, value.terminals.gpuBytes - bytes);
        if (frame.visible) for (const lod of [4, 3, 2, 'coarse', 'occluded']) frame.stats.terminals[lod] += value.terminals.counts[lod];
        frame.pinned.add(term);
        b.drawn = { url: term, version: value.version, kind: 'terminal' };
    }

    // A tree batch. While the service serves species impostors, each tree beyond the tree cut's
    // distance (from the profile's tree_geometric_error; Infinity when it is 0)
    // is a billboard (its position and parameters from the batch's extruded set) and each
    // nearer one is drawn from the batch's terminals, which a batch fetches only while its
    // cell is within that distance; a tree of no served species (edited, its species not baked
    // yet) is terminals at any distance. Without species impostors only near batches draw,
    // from their terminals. Until the terminals arrive every tree of a near batch is a
    // billboard, so none blinks out.
    updateTrees(b, decision, treeDistance, frame) {
        if (this.treeForm === 'none') {
            b.shown = { extruded: null, terminal: null };
            b.drawn = null;
            return;
        }
        // Near trees whose terminal set the budget holds back are billboards too.
        const near = this.treesNear(decision, treeDistance) && !frame.heldBack.has(b.terminal_set);
        let boards = null;
        if (this.treesAsBillboards()) {
            this.request(b, 'extruded', frame);
            const ext = this.pick(b.extruded_set, b.shown.extruded);
            if (ext && this.trees.isReady) {
                const value = this.cache.get(ext);
                boards = { url: ext, value, group: this.object(ext, value, 'billboards'), trees: value.billboards };
            }
        }
        const wantTerminals = near || (boards && boards.trees.unmatched > 0);
        if (wantTerminals) this.request(b, 'terminal', frame);
        const term = wantTerminals ? this.pickTerminals(b) : null;
        b.shown = { extruded: boards?.url ?? null, terminal: term };
        const { local, stats, visible } = frame;
        // Near, with its terminals in, the cut is by distance; else every tree that can be is far,
        // a billboard or a point (far, only the edited trees' terminals are drawn).
        if (boards) boards.trees.updateCut(local, term && near ? treeDistance : 0, frame.occlusion, frame.treePoints);
        if (term) this.showTerminals(b, term, frame, boards?.trees ?? null);
        if (boards) {
            frame.pinned.add(boards.url);
            frame.objects.push(boards.group);
            if (!term) b.drawn = { url: boards.url, version: boards.value.version, kind: 'billboards' };
        }
        if (!term && !boards) b.drawn = null;
        if (!visible) return;
        const members = boards?.trees.speciesOfTree.length ?? b.members;
        // Far trees the occlusion tiles hide count as billboards (the stats panel says how
        // many are hidden), not drawn.
        const billboards = (boards?.trees.count ?? 0) + (boards?.trees.occluded ?? 0);
        const points = boards?.trees.pointCount ?? 0;
        stats.trees.billboards += billboards;
        stats.trees.points += points;
        stats.trees.occluded += boards?.trees.occluded ?? 0;
        if (term) stats.trees.terminals += members - billboards - points;
        if (term && !near) stats.trees.edited += boards.trees.unmatched;
    }

    // The batch versions drawn now that differ from 1 (edited), and those of `cell` if given.
    versions(cell) {
        const out = [];
        for (const c of this.cells)
            for (const b of c.batches)
                if (b.drawn && (b.drawn.version > 1 || c === cell)) out.push({ cell: c.id, grammar: b.grammar, version: b.drawn.version, kind: b.drawn.kind });
        return out;
    }
}
