// The ray-cast ground's picking (src/render/ground.js): a ray hits the plane z = height where
// it crosses it, within the raycaster's range, and never from above the horizon. Its pixels are
// checked in the browser test (trees.e2e.mjs), against the scene drawn without it.
import assert from 'node:assert/strict';
import test from 'node:test';
import * as THREE from 'three';

import { Ground } from '../src/render/ground.js';

const lighting = {
    sunDirection: new THREE.Vector3(0, 0.6, 0.8),
    sunColour: new THREE.Color(1, 1, 1),
    skyColour: new THREE.Color(0.25, 0.25, 0.25),
    groundColour: new THREE.Color(0.05, 0.05, 0.05),
};

function hits(ground, origin, direction, near = 0, far = Infinity) {
    const raycaster = new THREE.Raycaster(new THREE.Vector3(...origin), new THREE.Vector3(...direction).normalize(), near, far);
    return raycaster.intersectObject(ground.mesh);
}

test('a ray hits the ground plane where it crosses it', () => {
    const ground = new Ground(new THREE.Color(0.5, 0.5, 0.5), lighting);
    ground.height = -2;
    const [hit] = hits(ground, [0, 0, 0], [0, 1, -1]);
    assert.equal(hit.object, ground.mesh);
    assert.ok(Math.abs(hit.distance - 2 * Math.SQRT2) < 1e-9);
    assert.ok(hit.point.distanceTo(new THREE.Vector3(0, 2, -2)) < 1e-9);
    // Far out, as a ray just under the horizon meets it.
    const [far] = hits(ground, [0, 0, 0], [1, 0, -1e-4]);
    assert.ok(Math.abs(far.point.x - 2e4) < 1e-6 && Math.abs(far.point.z + 2) < 1e-9);
});

test('no hit above the horizon, from under the plane, or outside the raycaster\'s range', () => {
    const ground = new Ground(new THREE.Color(0.5, 0.5, 0.5), lighting);
    ground.height = -2;
    assert.equal(hits(ground, [0, 0, 0], [0, 1, 0]).length, 0);
    assert.equal(hits(ground, [0, 0, 0], [0, 1, 0.1]).length, 0);
    assert.equal(hits(ground, [0, 0, -5], [0, 1, -1]).length, 0, 'the plane is above a ray from under it going down');
    assert.equal(hits(ground, [0, 0, 0], [0, 0, -1], 0, 1.5).length, 0);
    assert.equal(hits(ground, [0, 0, 0], [0, 0, -1], 2.5).length, 0);
    assert.equal(hits(ground, [0, 0, 0], [0, 0, -1], 1.5, 2.5).length, 1);
});

test('it is lit as a Lambert surface facing up', () => {
    const ground = new Ground(new THREE.Color(0.5, 0.4, 0.2), lighting);
    // albedo * (sky + sun * cos), cos = 0.8: facing up, the hemisphere light gives its sky colour
    const lit = ground.material.uniforms.litColour.value;
    assert.ok(Math.abs(lit.r - 0.5 * 1.05) < 1e-6 && Math.abs(lit.g - 0.4 * 1.05) < 1e-6 && Math.abs(lit.b - 0.2 * 1.05) < 1e-6);
});
