// The viewer's lighting (src/render/lights.js): the hemisphere light points along world up, and
// lambertLight gives what three.js's Lambert shading gives a normal under those lights. The
// browser test (impostor.e2e.mjs) checks the GLSL twin against MeshLambertMaterial's pixels.
import assert from 'node:assert/strict';
import test from 'node:test';
import * as THREE from 'three';

import { lambertLight, makeLights, WORLD_UP } from '../src/render/lights.js';

const close = (a, b, what) =>
    assert.ok(Math.abs(a.r - b.r) < 1e-9 && Math.abs(a.g - b.g) < 1e-9 && Math.abs(a.b - b.b) < 1e-9, `${what}: ${a.toArray()} against ${b.toArray()}`);

test('the sky hemisphere is aimed at world up, not three.js\'s default +y', () => {
    const { lights } = makeLights();
    const sky = lights.find((l) => l.isHemisphereLight);
    assert.ok(sky, 'a hemisphere light');
    assert.ok(sky.position.clone().normalize().distanceTo(WORLD_UP) < 1e-12, `aimed at ${sky.position.toArray()}`);
    const sun = lights.find((l) => l.isDirectionalLight);
    assert.ok(sun.position.z > 0, 'the sun is above the horizon');
});

test('the shader terms are three.js\'s light colours over pi', () => {
    const { lights, lighting } = makeLights();
    const sky = lights.find((l) => l.isHemisphereLight), sun = lights.find((l) => l.isDirectionalLight);
    close(lighting.skyColour, sky.color.clone().multiplyScalar(sky.intensity / Math.PI), 'sky');
    close(lighting.groundColour, sky.groundColor.clone().multiplyScalar(sky.intensity / Math.PI), 'ground');
    close(lighting.sunColour, sun.color.clone().multiplyScalar(sun.intensity / Math.PI), 'sun');
    assert.ok(lighting.sunDirection.clone().sub(sun.position.clone().normalize()).length() < 1e-12);
});

test('up gets the sky, down the ground, a facade their mean, each plus its share of the sun', () => {
    const { lighting } = makeLights();
    const sunOn = (n) => lighting.sunColour.clone().multiplyScalar(Math.max(n.dot(lighting.sunDirection), 0));
    close(lambertLight(lighting, WORLD_UP), lighting.skyColour.clone().add(sunOn(WORLD_UP)), 'a roof');
    const down = new THREE.Vector3(0, 0, -1);
    close(lambertLight(lighting, down), lighting.groundColour.clone(), 'an underside (no sun)');
    const mean = lighting.skyColour.clone().lerp(lighting.groundColour, 0.5);
    // North and south facades alike: the hemisphere is about z, so only the sun tells them apart.
    for (const [name, n] of [['north', new THREE.Vector3(0, 1, 0)], ['south', new THREE.Vector3(0, -1, 0)], ['east', new THREE.Vector3(1, 0, 0)]])
        close(lambertLight(lighting, n), mean.clone().add(sunOn(n)), `a ${name} facade`);
});
