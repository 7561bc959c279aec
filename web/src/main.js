// The hexlod browser viewer: loads the scene summary and the cell index, then every frame moves
// the camera, lets the streamer decide and fetch what each cell needs, renders camera-relative
// and refreshes the panels. Edits come back as change events and re-render the cells they
// touched. `window.hexlod` exposes the state for tests and the console.
import { getJson, traffic } from './api.js';
import { CameraControls } from './camera/controls.js';
import { EditClient } from './edits/edit_client.js';
import { makeBuildingPointMaterial } from './render/building_points.js';
import { makeExtrudedMaterial } from './render/extruded_mesh.js';
import { ImpostorSet } from './render/impostors.js';
import { isSoftwareRenderer, OccluderDepth } from './render/occluder_depth.js';
import { TreeImpostors } from './render/tree_impostors.js';
import { ShapeLibrary } from './render/shape_library.js';
import { World } from './render/world.js';
import { Streamer } from './stream/streamer.js';
import { showAttribution } from './ui/attribution.js';
import { Messages } from './ui/messages.js';
import { Picker } from './ui/picker.js';
import { queryCamera, queryChoice, queryNumber } from './ui/query_options.js';
import { StatsPanel } from './ui/stats_panel.js';
import { TuningPanel } from './ui/tuning_panel.js';
import * as THREE from 'three';

const params = new URLSearchParams(location.search);
const messages = new Messages(document.getElementById('messages'));
const stats = new StatsPanel(document.getElementById('stats'));
const canvas = document.getElementById('view');

// The opening view: above the south of the city, looking north over it, unless ?camera=x,y,z,yaw,pitch (degrees).
function openingCamera(cells) {
    const { value: given, problem } = queryCamera(params);
    if (problem) messages.add(problem);
    if (given) return given;
    const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
    for (const c of cells)
        for (let i = 0; i < 3; ++i) {
            min[i] = Math.min(min[i], c.bounds.min[i]);
            max[i] = Math.max(max[i], c.bounds.max[i]);
        }
    if (!cells.length) return { position: [0, -100, 50], yaw: Math.PI / 2, pitch: -0.3 };
    const centre = [(min[0] + max[0]) / 2, (min[1] + max[1]) / 2, min[2]];
    const extent = Math.max(max[0] - min[0], max[1] - min[1], 50);
    const position = [centre[0], centre[1] - 0.75 * extent, centre[2] + 0.35 * extent];
    return { position, yaw: Math.PI / 2, pitch: -Math.atan2(0.35 * extent, 0.75 * extent) };
}

async function start() {
    const scene = await getJson('/api/v1/scene');
    let index = await getJson('/api/v1/cells');
    document.title = `hexlod: ${scene.name}`;
    showAttribution(document.getElementById('attribution'), scene);
    const antialias = params.get('aa') !== '0';
    const world = new World(canvas, { antialias });
    const capabilities = scene.capabilities ?? {};
    if (!capabilities.terminal_meshes) messages.add('terminal meshes are not served by this service: LOD4 draws stand-in quads', 'notice');
    if (!capabilities.impostors) messages.add('impostors are not served by this service: every terminal is drawn at LOD4', 'notice');
    const libraries = {};
    // ?coarse=0 draws LOD4 terminals with their full meshes at any distance, for comparisons.
    const coarse = params.get('coarse') !== '0';
    for (const g of scene.grammars) libraries[g.index] = new ShapeLibrary(g, { meshes: !!capabilities.terminal_meshes, coarse });
    const impostors = new ImpostorSet(scene, world.lighting);
    // ?treeboxes=0 draws each tree billboard over its sphere's whole square, and ?treepoints=0
    // keeps far trees' billboards instead of drawing them as points, for comparisons.
    const trees = new TreeImpostors(scene, world.lighting, { multisampled: antialias, boxes: params.get('treeboxes') !== '0', points: params.get('treepoints') !== '0' });
    if (scene.counts?.trees > 0 && !capabilities.tree_billboards)
        messages.add('tree impostors are not served by this service: trees beyond the terminal distance are not drawn', 'notice');
    const terminal = new THREE.MeshLambertMaterial({ vertexColors: true });
    // ?points=0 keeps far buildings' shells instead of drawing them as points, for comparisons.
    const points = params.get('points') !== '0' ? makeBuildingPointMaterial(world.lighting) : null;
    const materials = { extruded: makeExtrudedMaterial(), backing: new THREE.MeshLambertMaterial({ vertexColors: true }), terminal, points };
    // ?budget=MiB bounds the content cache, and with it the terminal sets a view may hold. The
    // default holds the thesis city's street view whole (0.93 GB: docs/BENCHMARKS.md, "The
    // viewer's memory within its budget").
    const budget = queryNumber(params, 'budget', { fallback: 1024, min: 0, max: 65536 });
    const concurrency = queryNumber(params, 'concurrency', { fallback: 6, min: 1, max: 64, integer: true });
    const treeForm = queryChoice(params, 'trees', ['auto', 'terminals', 'billboards', 'none'], 'auto');
    const mode = queryChoice(params, 'mode', ['fly', 'walk'], 'fly');
    for (const { problem } of [budget, concurrency, treeForm, mode]) if (problem) messages.add(problem);
    // ?occlusion=1 or 0 turns occlusion culling on or off; by default it is on where the GL
    // renders on the CPU.
    const occlusionParam = params.get('occlusion');
    const occlusion = occlusionParam === null ? isSoftwareRenderer(world.renderer) : occlusionParam !== '0';
    const occlusionStatus = occlusion ? `occlusion on${occlusionParam === null ? ' (software GL)' : ''}` : 'occlusion off';
    const streamer = new Streamer({
        scene,
        world,
        libraries,
        impostors,
        trees,
        treeForm: treeForm.value,
        materials,
        budgetBytes: budget.value * 1024 * 1024,
        concurrency: concurrency.value,
        onError: (text) => messages.add(text),
        onStale: () => reloadIndex(),
        occluders: occlusion ? new OccluderDepth(world) : null,
    });
    streamer.setIndex(index);

    const groundAt = (p) => {
        const cell = streamer.cells.find((c) => p[0] >= c.bounds.min[0] && p[0] <= c.bounds.max[0] && p[1] >= c.bounds.min[1] && p[1] <= c.bounds.max[1]);
        return cell ? cell.origin[2] : world.groundZ;
    };
    world.groundZ = streamer.cells.length ? Math.min(...streamer.cells.map((c) => c.origin[2])) : 0;
    const controls = new CameraControls(canvas, { ...openingCamera(index.cells), groundAt });
    if (mode.value === 'walk') controls.setMode('walk');

    let reloading = null;
    async function reloadIndex() {
        if (reloading) return reloading;
        reloading = getJson('/api/v1/cells')
            .then((fresh) => {
                index = fresh;
                streamer.setIndex(fresh);
                edits.indexSeq = fresh.seq;
            })
            .catch((e) => messages.add(`cell index: ${e.message}`))
            .finally(() => (reloading = null));
        return reloading;
    }
    const edits = new EditClient({
        onChanged: (changed) => {
            streamer.applyChanged(changed);
            stream(performance.now()); // ask for the new content now, not at the next frame
        },
        onReset: () => reloadIndex(),
        onStatus: (s) => (eventStatus = s),
        onSpecies: (entry) => trees.add(entry).then((added) => added && stream(performance.now())),
        onSpeciesCount: (count) => {
            if (count > trees.species.length)
                getJson('/api/v1/scene')
                    .then((fresh) => Promise.all((fresh.tree_species ?? []).map((entry) => trees.add(entry))))
                    .catch((e) => messages.add(`tree species: ${e.message}`));
        },
    });
    let eventStatus = 'events: connecting';
    edits.indexSeq = index.seq;
    edits.connect();

    const picker = new Picker(world, scene);
    const tuning = new TuningPanel(document.getElementById('tuning'), { scene, edits, messages });
    tuning.select(null);
    let selection = null;
    function select(picked) {
        selection = picked;
        tuning.select(picked);
        outlineSelection();
    }
    // Outlines the selected building from the extruded set its cell draws, again whenever that
    // changes (an edit's new version arrived).
    let outlined = null;
    function outlineSelection() {
        const cell = selection?.cell && streamer.cells.find((c) => c.q === selection.cell[0] && c.r === selection.cell[1]);
        const batch = cell?.batches.find((b) => b.grammar === selection.grammar);
        const url = batch?.shown.extruded;
        if (outlined && outlined.url === url && outlined.selection === selection) return;
        outlined = { url, selection };
        const value = url ? streamer.cache.get(url) : null;
        picker.outlineBuilding(selection?.building, cell ? world.cellGroup(cell) : null, value?.set, cell?.origin);
    }
    canvas.addEventListener('pointerup', (e) => {
        if (controls.dragged > 4) return;
        select(picker.pick(e.clientX, e.clientY, canvas));
    });

    const resize = () => world.resize(canvas.clientWidth, canvas.clientHeight);
    window.addEventListener('resize', resize);
    resize();

    const startedAt = performance.now();
    let loadTime = null, last = performance.now(), lastStats = 0, lastStream = 0;
    function stream(now, view = controls.view(canvas.clientHeight)) {
        world.place(view);
        streamer.update(view, world.camera);
        lastStream = now;
        if (selection) outlineSelection();
    }
    // While this viewer's edit waits for its reply, and then for its new content, the viewer
    // starts no frame, for at most half a second each: on a slow renderer a frame holds the
    // main thread for hundreds of milliseconds, and the reply and the payloads, which the
    // service sends within milliseconds, would wait behind several frames.
    function awaitingEdit(now) {
        if (edits.postingSince !== null) return now - edits.postingSince < 500;
        const post = edits.lastPost;
        return post !== null && post.shownAt === null && now - post.repliedAt < 500 && streamer.fetchesAnyOf(post.changed);
    }
    function frame(now) {
        if (awaitingEdit(now)) {
            requestAnimationFrame(frame);
            return;
        }
        const dt = Math.min((now - last) / 1000, 0.1);
        last = now;
        controls.update(dt);
        const view = controls.view(canvas.clientHeight);
        if (now - lastStream > 50) stream(now, view);
        world.render(view);
        const post = edits.lastPost;
        if (post && post.shownAt === null) {
            const drawn = streamer.drawsVersions(post.changed);
            if (drawn !== false) Object.assign(post, { shownAt: now, inView: drawn === true });
        }
        stats.frame(now);
        if (loadTime === null && streamer.queue.pending === 0 && streamer.cache.size > 0) loadTime = (now - startedAt) / 1000;
        if (now - lastStats > 250) {
            lastStats = now;
            stats.show(state());
        }
        requestAnimationFrame(frame);
    }
    function state() {
        return {
            mode: controls.mode,
            speed: controls.speed,
            position: controls.position,
            streamer: streamer.stats,
            traffic: { ...traffic },
            cache: { entries: streamer.cache.size, bytes: streamer.cache.bytes, budget: streamer.cache.budget, evictions: streamer.cache.evictions },
            terminalBudget: { ...streamer.budget }, // what the latest update's admission had and took
            pending: streamer.queue.pending,
            inFlight: streamer.queue.inFlight,
            aborted: streamer.queue.aborted,
            meshes: capabilities.terminal_meshes ? Object.values(libraries).map((l) => l.status).join(', ') : 'stand-ins (not served: capabilities.terminal_meshes is false)',
            impostors: capabilities.impostors ? impostors.status : 'off (not served: capabilities.impostors is false)',
            trees: capabilities.tree_billboards ? trees.status : 'off (not served: capabilities.tree_billboards is false)',
            occlusion: occlusion ? `${occlusionStatus}, ${streamer.stats.terminals.occluded} hidden` : occlusionStatus,
            loadTime,
            lastEdit: edits.lastPost ?? null,
            versions: streamer.versions(selection?.cell && streamer.cells.find((c) => c.q === selection.cell[0] && c.r === selection.cell[1])),
            events: eventStatus,
            fps: stats.fps,
            triangles: world.renderer.info.render.triangles, // of the last frame
        };
    }
    requestAnimationFrame(frame);

    window.hexlod = {
        scene,
        streamer,
        controls,
        world,
        state,
        setCamera: (c) => controls.set(c),
        select: (picked) => select(picked),
        tuning,
        pickAt: (x, y) => picker.pick(x, y, canvas),
        selectionRect: () => picker.screenRect(canvas),
        // Nothing loading, and the lists sorted with the latest occlusion image.
        idle: () => loadTime !== null && streamer.queue.pending === 0 && streamer.queue.inFlight === 0 && (streamer.occluders?.settled ?? true),
    };
}

start().catch((e) => {
    messages.add(`the viewer could not start: ${e.message}`);
    console.error(e);
});
