// The viewer's LOD policy against the native one (cells/src/scheduler.cpp, lod/src/cull_inputs.cpp,
// lod/include/hexlod/lod/cull_shared.h): the screen-space error formula, the hysteresis band, the
// distance to a cell's bounds, the per-terminal LOD distances and the backface rule; the view
// test that leaves terminals outside the frustum out; the coarse mesh's range (meshShape); and
// when a moved or turned camera re-decides them.
import assert from 'node:assert/strict';
import test from 'node:test';

import {
    classifyTerminal,
    COARSE,
    coarseMeshReach,
    decideCell,
    distanceToBox,
    EXTRUDED,
    lodDistance,
    movedEnough,
    nextCellLod,
    outsideView,
    screenSpaceError,
    TERMINALS,
    terminalLodDistances,
    TURN_MARGIN,
    turnedEnough,
} from '../src/stream/lod_policy.js';
import { degrees, viewAlong } from './views.js';

const profile = { max_screen_space_error: 2, hysteresis: 0.2, geometric_error: [16, 4, 1, 0.25, 0] };
const camera = { position: [0, 0, 10], fovY: Math.PI / 3, viewportHeight: 720 };

test('screen-space error is the 3D Tiles formula and infinite inside the bounds', () => {
    assert.equal(screenSpaceError(4, 100, 720, Math.PI / 3), (4 * 720) / (100 * 2 * Math.tan(Math.PI / 6)));
    assert.equal(screenSpaceError(4, 0, 720, 1), Infinity);
    // Where LOD1's error equals the budget: 4 m at 720 px, 60 degrees, 2 px.
    const d = lodDistance(4, profile, Math.PI / 3, 720);
    assert.ok(Math.abs(screenSpaceError(4, d, 720, Math.PI / 3) - 2) < 1e-12);
    assert.ok(Math.abs(d - 1247.0765814495915) < 1e-9);
});

test('the hysteresis band keeps the previous LOD between max_sse * (1 -+ band)', () => {
    assert.equal(nextCellLod(EXTRUDED, 2.41, profile), TERMINALS);
    assert.equal(nextCellLod(EXTRUDED, 2.39, profile), EXTRUDED);
    assert.equal(nextCellLod(TERMINALS, 1.61, profile), TERMINALS);
    assert.equal(nextCellLod(TERMINALS, 1.59, profile), EXTRUDED);
    assert.equal(nextCellLod(TERMINALS, 2, profile), TERMINALS);
    assert.equal(nextCellLod(EXTRUDED, 2, profile), EXTRUDED);
});

test('cells are judged by the distance to their bounds box and start extruded', () => {
    assert.equal(distanceToBox([0, 0, 0], [3, 4, -1], [5, 6, 1]), 5);
    assert.equal(distanceToBox([4, 5, 0], [3, 4, -1], [5, 6, 1]), 0);
    const inside = decideCell(undefined, { min: [-1, -1, 0], max: [1, 1, 20] }, camera, profile);
    assert.deepEqual([inside.distance, inside.sse, inside.lod], [0, Infinity, TERMINALS]);
    const far = decideCell(undefined, { min: [5000, 0, 0], max: [5100, 10, 10] }, camera, profile);
    assert.equal(far.lod, EXTRUDED);
    assert.equal(far.distance, 5000);
});

test('terminals: LOD3 and LOD2 distances from their geometric errors; backfaces culled', () => {
    const { lod3, lod2 } = terminalLodDistances(profile, camera);
    assert.ok(Math.abs(lod3 - (0.25 * 720) / (2 * Math.tan(Math.PI / 6) * 2)) < 1e-9);
    assert.ok(Math.abs(lod2 - (1 * 720) / (2 * Math.tan(Math.PI / 6) * 2)) < 1e-9);
    // A 2 x 3 m terminal on a wall facing -y (its normal), axes X = +x, Y = +z, Z = -y.
    const axes = [1, 0, 0, 0, 0, 1, 0, -1, 0];
    const at = (y) => [-1, y, -1.5]; // the corner relative to the camera: the wall at distance y
    assert.equal(classifyTerminal(at(10), axes, 2, 3, 0.3, { lod3, lod2 }, true), 4);
    assert.equal(classifyTerminal(at(lod3 + 1), axes, 2, 3, 0.3, { lod3, lod2 }, true), 3);
    assert.equal(classifyTerminal(at(lod2 + 1), axes, 2, 3, 0.3, { lod3, lod2 }, true), 2);
    assert.equal(classifyTerminal(at(lod2 + 1), axes, 2, 3, 0.3, { lod3, lod2 }, false), 4);
    // Behind the wall: the camera at y > wall + depth sees its back.
    assert.equal(classifyTerminal(at(-0.5), axes, 2, 3, 0.3, { lod3, lod2 }, true), 0);
    assert.equal(classifyTerminal(at(-0.2), axes, 2, 3, 0.3, { lod3, lod2 }, true), 4);
    // A tree's part stands free: from behind, its other side shows.
    assert.equal(classifyTerminal(at(-0.5), axes, 2, 3, 0.3, { lod3, lod2 }, false, null, 0, Infinity, null, false), 4);
    assert.equal(classifyTerminal(at(-50), axes, 2, 3, 0.3, { lod3, lod2 }, false, null, 0, Infinity, null, false), 4);
});

test('a coarse mesh is drawn from where its deviation, scaled by the scope, projects under the budget', () => {
    const { coarse } = terminalLodDistances(profile, camera);
    // meshShape's reach: |deviation * scope| * (viewport pixels per radian / max sse).
    assert.ok(Math.abs(coarse - 720 / (2 * Math.tan(Math.PI / 6) * 2)) < 1e-9);
    const reach = coarseMeshReach([0.01, 0.02, 0.1], 2, 3, 0.3, coarse);
    assert.ok(Math.abs(reach - Math.hypot(0.02, 0.06, 0.03) * coarse) < 1e-9);
    const axes = [1, 0, 0, 0, 0, 1, 0, -1, 0];
    const at = (y) => [-1, y, -1.5]; // the scope centre straight ahead at distance y
    const distances = terminalLodDistances(profile, camera);
    assert.equal(classifyTerminal(at(reach + 0.01), axes, 2, 3, 0.3, distances, false, null, 0, reach), COARSE);
    assert.equal(classifyTerminal(at(reach - 0.01), axes, 2, 3, 0.3, distances, false, null, 0, reach), 4);
    // The camera may move by `slack` before the lists are sorted again: the coarse mesh starts that much farther.
    assert.equal(classifyTerminal(at(reach + 0.4), axes, 2, 3, 0.3, distances, false, null, 0.5, reach), 4);
    assert.equal(classifyTerminal(at(reach + 0.6), axes, 2, 3, 0.3, distances, false, null, 0.5, reach), COARSE);
    // A shape with an impostor draws it from the same distance to LOD3's, its impostors beyond.
    assert.ok(distances.lod3 > reach + 1);
    assert.equal(classifyTerminal(at(reach - 0.01), axes, 2, 3, 0.3, distances, true, null, 0, reach), 4);
    assert.equal(classifyTerminal(at(reach + 1), axes, 2, 3, 0.3, distances, true, null, 0, reach), COARSE);
    assert.equal(classifyTerminal(at(distances.lod3 + 1), axes, 2, 3, 0.3, distances, true, null, 0, reach), 3);
    // Shapes without a coarse mesh never draw one.
    assert.equal(classifyTerminal(at(1e5), axes, 2, 3, 0.3, distances, false), 4);
});

test('a distance decision is re-made once the camera moves 2 % of the distance, at least 0.5 m', () => {
    assert.equal(movedEnough(null, [0, 0, 0], 100), true);
    assert.equal(movedEnough([0, 0, 0], [1.9, 0, 0], 100), false);
    assert.equal(movedEnough([0, 0, 0], [0, 2, 0], 100), true);
    assert.equal(movedEnough([0, 0, 0], [0, 0, 0.4], 1), false); // the half-metre floor
    assert.equal(movedEnough([0, 0, 0], [0, 0, 0.5], 1), true);
});

const alongY = viewAlong([0, 1, 0]);

test('a terminal outside the view, with the turn margin, is left out', () => {
    assert.equal(TURN_MARGIN, degrees(10));
    assert.equal(outsideView(alongY, 0, 100, 0, 1), false); // ahead
    assert.equal(outsideView(alongY, 0, -100, 0, 1), true); // behind
    assert.equal(outsideView(alongY, 0, -1, 0, 2), false); // behind, but reaching into the view
    // 5 degrees past the 45 degree edge is within the margin; 15 degrees is not.
    const at = (a) => [100 * Math.sin(degrees(a)), 100 * Math.cos(degrees(a)), 0];
    assert.equal(outsideView(alongY, ...at(50), 0.1), false);
    assert.equal(outsideView(alongY, ...at(60), 0.1), true);
    assert.equal(outsideView(alongY, ...at(-60), 0.1), true);
    // The radius counts: a large sphere whose edge reaches the widened plane stays.
    assert.equal(outsideView(alongY, ...at(60), 20), false);
    // Above and below too.
    assert.equal(outsideView(alongY, 0, 100, 150, 1), true);
    assert.equal(outsideView(alongY, 0, 100, -150, 1), true);
});

test('classifyTerminal culls a terminal outside the view, widened by the camera\'s slack', () => {
    const { lod3, lod2 } = terminalLodDistances(profile, camera);
    const axes = [1, 0, 0, 0, 0, 1, 0, -1, 0]; // a 2 x 3 m terminal on a wall facing -y
    const corner = (x, y) => [x - 1, y, -1.5]; // centre (x, y, 0) relative to the camera
    assert.equal(classifyTerminal(corner(0, 10), axes, 2, 3, 0.3, { lod3, lod2 }, true, alongY), 4);
    assert.equal(classifyTerminal(corner(0, 10), axes, 2, 3, 0.3, { lod3, lod2 }, true, null), 4);
    // 60 m to the side at 15 m ahead: outside (76 degrees off the axis), but not with 50 m of slack.
    assert.equal(classifyTerminal(corner(60, 15), axes, 2, 3, 0.3, { lod3, lod2 }, true, alongY), 0);
    assert.equal(classifyTerminal(corner(60, 15), axes, 2, 3, 0.3, { lod3, lod2 }, true, alongY, 50), 4);
});

test('a view decision is re-made once the view turns by half the margin', () => {
    const turned = (d) => [Math.sin(degrees(d)), Math.cos(degrees(d)), 0];
    assert.equal(turnedEnough(null, [0, 1, 0]), true);
    assert.equal(turnedEnough([0, 1, 0], turned(4.9)), false);
    assert.equal(turnedEnough([0, 1, 0], turned(5.1)), true);
    assert.equal(turnedEnough([0, 1, 0], [0, -1, 0]), true);
});
