// A page for impostor.e2e.mjs: the viewer's impostor material (render/impostors.js) drawing one
// terminal from a synthetic 4 x 4 atlas whose every view is an opaque tile of its own colour
// (red = 16 x view index), seen from straight in front; LOD2 covers its mesh bounds' rectangle. The service this build talks to bakes
// no impostors, so this is how the LOD2 and LOD3 shaders get compiled and checked at all.
import * as THREE from 'three';

import { ImpostorSet } from '../src/render/impostors.js';
import { makeLights } from '../src/render/lights.js';

const grid = 4, resolution = 16, padding = 1, size = grid * resolution;
const layout = { sphere: 'hemi-octahedral', grid, view_resolution: resolution, padding, central_view: 5 };
const albedoTexels = new Uint8Array(size * size * 4), normalTexels = new Uint8Array(size * size * 4);
for (let y = 0; y < size; ++y)
    for (let x = 0; x < size; ++x) {
        const tx = x % resolution, ty = y % resolution, view = Math.floor(y / resolution) * grid + Math.floor(x / resolution);
        const inner = tx >= padding && tx < resolution - padding && ty >= padding && ty < resolution - padding;
        // Premultiplied, as the viewer uploads its albedo atlases: an empty texel is all zero.
        albedoTexels.set(inner ? [view * 16, 255 - view * 16, 128, 255] : [0, 0, 0, 0], 4 * (y * size + x));
        normalTexels.set([128, 128, 255, 128], 4 * (y * size + x));
    }
const texture = (texels, colorSpace) => {
    const t = new THREE.DataTexture(texels, size, size);
    t.colorSpace = colorSpace;
    t.needsUpdate = true;
    return t;
};
const canvas = document.createElement('canvas');
canvas.width = canvas.height = 128;
document.body.append(canvas);
const renderer = new THREE.WebGLRenderer({ canvas, preserveDrawingBuffer: true });
// Unlit: a white sky and ground and no sun, so that a pixel shows its view's albedo.
const white = new THREE.Color(1, 1, 1);
const lighting = { sunDirection: new THREE.Vector3(0, -1, 1).normalize(), sunColour: new THREE.Color(0, 0, 0), skyColour: white, groundColour: white };
const impostors = new ImpostorSet({ capabilities: { impostors: true }, impostor_layout: layout, grammars: [] }, lighting);
const atlas = {
    albedo: texture(albedoTexels, THREE.SRGBColorSpace),
    normal: texture(normalTexels, THREE.NoColorSpace),
    nominal: [1, 2, 0.2],
    impostor: { centre: [0.5, 1, 0.1], radius: 1.2, bounds_min: [0, 0, -0.1], bounds_max: [1, 2, 0.3] },
    materials: {},
};
const camera = new THREE.PerspectiveCamera(60, 1, 0.1, 100);
camera.up.set(0, 0, 1);
camera.position.set(0.5, -6, 1);
camera.lookAt(0.5, 0, 1);
const results = {};
const errors = [];
renderer.debug.onShaderError = (gl, program) => errors.push(gl.getProgramInfoLog(program) || 'shader error');
for (const lod of [2, 3]) {
    const scene = new THREE.Scene();
    scene.background = new THREE.Color(0, 0, 0);
    const mesh = impostors.makeMesh(atlas, lod, 1);
    // A 1 x 2 m terminal on a wall facing -y (X = +x, Y = +z, Z = -y), 0.2 m deep.
    mesh.setMatrixAt(0, new THREE.Matrix4().set(1, 0, 0, 0, 0, 0, -0.2, 0, 0, 2, 0, 0, 0, 0, 0, 1));
    scene.add(mesh);
    renderer.render(scene, camera);
    const gl = renderer.getContext();
    const pixels = new Uint8Array(4 * 128 * 128);
    gl.readPixels(0, 0, 128, 128, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    let covered = 0;
    for (let i = 0; i < pixels.length; i += 4) if (pixels[i + 3] === 255 && pixels[i] + pixels[i + 1] > 0) ++covered;
    const centre = 4 * (64 * 128 + 64);
    results[lod] = { covered, centre: Array.from(pixels.subarray(centre, centre + 3)) };
}
// The pixels of the mesh bounds' rectangle on the wall plane (world y = 0), which LOD2 covers.
const corner = (x, z) => new THREE.Vector3(x, 0, z).project(camera).multiplyScalar(64);
const [low, high] = [corner(0, 0), corner(1, 2)];
results.wallRectangle = (high.x - low.x) * (high.y - low.y);

// Lit by the viewer's lights, LOD2 against a MeshLambertMaterial rectangle of the central view's
// albedo in its place, facing each way: the centre pixels must match, as an impostor and its
// mesh must across the LOD switch. Terminal axes X (1 m), Y (2 m) and Z, the facade normal.
const lit = makeLights();
const litImpostors = new ImpostorSet({ capabilities: { impostors: true }, impostor_layout: layout, grammars: [] }, lit.lighting);
const litAtlas = { ...atlas, materials: {} };
const albedo = new THREE.Color().setRGB(80 / 255, 175 / 255, 128 / 255, THREE.SRGBColorSpace); // view 5
const v = (x, y, z) => new THREE.Vector3(x, y, z);
const facings = {
    south: [v(1, 0, 0), v(0, 0, 1), v(0, -1, 0)],
    north: [v(-1, 0, 0), v(0, 0, 1), v(0, 1, 0)],
    east: [v(0, 1, 0), v(0, 0, 1), v(1, 0, 0)],
    up: [v(1, 0, 0), v(0, 1, 0), v(0, 0, 1)],
};
const centrePixel = (object, x, y, z) => {
    const scene = new THREE.Scene();
    scene.background = new THREE.Color(0, 0, 0);
    scene.add(object, ...lit.lights.map((l) => l.clone()));
    const centre = x.clone().multiplyScalar(0.5).add(y);
    const view = new THREE.PerspectiveCamera(30, 1, 0.1, 100);
    view.up.copy(y);
    view.position.copy(centre).addScaledVector(z, 6);
    view.lookAt(centre);
    renderer.render(scene, view);
    const gl = renderer.getContext();
    const pixel = new Uint8Array(4);
    gl.readPixels(64, 64, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    return Array.from(pixel.subarray(0, 3));
};
results.lighting = {};
for (const [name, [x, y, z]] of Object.entries(facings)) {
    const impostor = litImpostors.makeMesh(litAtlas, 2, 1);
    impostor.setMatrixAt(0, new THREE.Matrix4().makeBasis(x, y.clone().multiplyScalar(2), z.clone().multiplyScalar(0.2)));
    const mesh = new THREE.Mesh(new THREE.PlaneGeometry(1, 2), new THREE.MeshLambertMaterial({ color: albedo }));
    mesh.matrixAutoUpdate = false;
    mesh.matrix.makeBasis(x, y, z).setPosition(x.clone().multiplyScalar(0.5).add(y));
    results.lighting[name] = { impostor: centrePixel(impostor, x, y, z), mesh: centrePixel(mesh, x, y, z) };
}
window.impostorResult = { results, errors };
