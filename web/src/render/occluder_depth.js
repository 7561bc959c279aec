// The depth image occlusion culling tests terminals against (stream/occlusion_tiles.js): the
// opaque base volumes (LOD0 extruded sets, and the volumes behind terminal facades), alone, at
// half the canvas's resolution, each pixel its linear view distance. The image is taken again
// once the camera has moved or turned a little, or the volumes drawn have changed; between
// two images a terminal's sphere is tested grown by how far the camera may have moved. What
// that growth does not cover is parallax between an occluder and what it hides over that
// metre: a terminal that comes into sight in it shows the volume behind it until the next image.
import * as THREE from 'three';

import { farthestPerTile, OcclusionTiles } from '../stream/occlusion_tiles.js';

// The three.js layer occluders are on, besides the default one.
export const OCCLUDER_LAYER = 1;
// Depth-image pixels per tile side (at half resolution, 16 canvas pixels, as the native tiles).
const TILE_PIXELS = 8;
// The camera moves at most this far (metres) and turns at most this much (radians) before the
// image is taken again.
const OCCLUSION_MOVE = 1.0;
const OCCLUSION_TURN = (1 * Math.PI) / 180;

// Linear view distance over the far distance, in 24 bits spread over red, green and blue.
const DEPTH_VERTEX = /* glsl */ `
out float vDistance;
void main() {
    vec4 view = modelViewMatrix * vec4(position, 1.0);
    vDistance = -view.z;
    gl_Position = projectionMatrix * view;
}
`;
const DEPTH_FRAGMENT = /* glsl */ `
uniform float far;
in float vDistance;
void main() {
    float v = floor(clamp(vDistance / far, 0.0, 1.0) * 16777215.0);
    float high = floor(v / 65536.0);
    float middle = floor((v - high * 65536.0) / 256.0);
    gl_FragColor = vec4(high, middle, v - high * 65536.0 - middle * 256.0, 255.0) / 255.0;
}
`;

export class OccluderDepth {
    constructor(world) {
        this.world = world;
        this.target = new THREE.WebGLRenderTarget(1, 1, { depthBuffer: true });
        this.material = new THREE.ShaderMaterial({ vertexShader: DEPTH_VERTEX, fragmentShader: DEPTH_FRAGMENT, uniforms: { far: { value: 1 } } });
        this.camera = new THREE.PerspectiveCamera();
        this.camera.layers.set(OCCLUDER_LAYER);
        this.pixels = null;
        this.depths = null;
        this.snapshot = null;
        this.taken = null; // {position, forward, contentVersion, fov, aspect} of the snapshot
        this.version = 0;
    }

    // The snapshot for this view, taken again when the camera moved or turned enough since the
    // last one, or the volumes drawn changed (`contentVersion`). `view`: {position, forward}.
    update(view, contentVersion) {
        const camera = this.world.camera;
        const t = this.taken, p = view.position, f = view.forward;
        const still =
            t &&
            t.contentVersion === contentVersion &&
            t.fov === camera.fov &&
            t.aspect === camera.aspect &&
            Math.hypot(p[0] - t.position[0], p[1] - t.position[1], p[2] - t.position[2]) < OCCLUSION_MOVE &&
            t.forward[0] * f[0] + t.forward[1] * f[1] + t.forward[2] * f[2] > Math.cos(OCCLUSION_TURN);
        if (still) return this.snapshot;
        this.take(camera);
        this.taken = { position: p.slice(), forward: f.slice(), contentVersion, fov: camera.fov, aspect: camera.aspect };
        return this.snapshot;
    }

    take(camera) {
        const { renderer, scene } = this.world;
        const size = renderer.getDrawingBufferSize(new THREE.Vector2());
        const width = Math.max(1, Math.ceil(size.x / 2)), height = Math.max(1, Math.ceil(size.y / 2));
        if (this.target.width !== width || this.target.height !== height) {
            this.target.setSize(width, height);
            this.pixels = new Uint8Array(4 * width * height);
            this.depths = new Float32Array(width * height);
        }
        this.camera.copy(camera, false);
        this.camera.layers.set(OCCLUDER_LAYER);
        this.camera.updateMatrixWorld();
        this.material.uniforms.far.value = camera.far;
        const saved = { background: scene.background, fog: scene.fog, override: scene.overrideMaterial, target: renderer.getRenderTarget() };
        const clear = renderer.getClearColor(new THREE.Color()), clearAlpha = renderer.getClearAlpha();
        scene.background = null;
        scene.fog = null;
        scene.overrideMaterial = this.material;
        renderer.setRenderTarget(this.target);
        renderer.setClearColor(0xffffff, 1); // the far distance: nothing drawn
        renderer.clear();
        renderer.render(scene, this.camera);
        renderer.readRenderTargetPixels(this.target, 0, 0, width, height, this.pixels);
        renderer.setRenderTarget(saved.target);
        renderer.setClearColor(clear, clearAlpha);
        Object.assign(scene, { background: saved.background, fog: saved.fog, overrideMaterial: saved.override });

        const far = camera.far, px = this.pixels;
        for (let i = 0; i < width * height; ++i) {
            const v = px[4 * i] * 65536 + px[4 * i + 1] * 256 + px[4 * i + 2];
            this.depths[i] = v >= 16777215 ? Infinity : (v / 16777215) * far;
        }
        const e = camera.matrixWorldInverse.elements, p = camera.projectionMatrix.elements;
        const rotation = [e[0], e[1], e[2], e[4], e[5], e[6], e[8], e[9], e[10]];
        this.snapshot = new OcclusionTiles(farthestPerTile(this.depths, width, height, TILE_PIXELS), { rotation, scaleX: p[0], scaleY: p[5], near: camera.near }, ++this.version, OCCLUSION_MOVE);
    }

    dispose() {
        this.target.dispose();
        this.material.dispose();
    }
}

// Whether the GL renders on the CPU (SwiftShader, llvmpipe, softpipe): there occlusion culling
// pays for its depth image and its re-sorts many times over, and on a GPU it does not.
export function isSoftwareRenderer(renderer) {
    const gl = renderer.getContext();
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
    return /swiftshader|llvmpipe|softpipe|software/i.test(name);
}
