// The depth image occlusion culling tests terminals against (stream/occlusion_tiles.js): the
// opaque base volumes (LOD0 extruded sets, and the volumes behind terminal facades), alone, at
// half the canvas's resolution, each pixel its linear view distance.
//
// Culling applies while the camera stands still. Moving, every new image would sort every
// batch's lists again and upload them, and on SwiftShader a walk ran slower with culling than
// without it (docs/BENCHMARKS.md); standing, one image serves every frame. So update() gives
// no image while the camera moves (the lists are then sorted without culling, as they must
// be: what was hidden may come into sight), and once it stands still takes one from there,
// again whenever the base volumes drawn change. The image is read back without waiting (a
// fence): a read that waits stalls the page until the GL has finished every frame before it,
// hundreds of milliseconds on a software GL; it is used once it arrives, if the camera still
// stands where it was taken. Spheres are grown by SLACK, for a camera that moves between the
// update that sorted the lists and a frame drawn with them (updates run at most every 50 ms).
import * as THREE from 'three';

import { farthestPerTile, OcclusionTiles } from '../stream/occlusion_tiles.js';

// The three.js layer occluders are on, besides the default one.
export const OCCLUDER_LAYER = 1;
// Depth-image pixels per tile side (at half resolution, 16 canvas pixels, as the native tiles).
const TILE_PIXELS = 8;
// Metres every tested sphere is grown by.
const SLACK = 1.0;

// Whether two poses ({position, forward, fov, aspect}) are the same.
function samePose(a, b) {
    return a.fov === b.fov && a.aspect === b.aspect && a.position.every((v, i) => v === b.position[i]) && a.forward.every((v, i) => v === b.forward[i]);
}

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
        this.snapshot = null; // the latest image read back, an OcclusionTiles
        this.snapshotPose = null; // where it was taken
        this.taken = null; // the pose and occluderVersion of the latest image asked for
        this.lastPose = null; // the camera's at the last update
        this.pending = false; // whether an image is being read back
        this.arrived = false; // whether one arrived after the last update
        this.version = 0;
    }

    // Whether the lists can have been sorted with every image asked for: none is being read
    // back, and none arrived after the last update.
    get settled() {
        return !this.pending && !this.arrived;
    }

    // The image to cull with for this view, or null: while the camera moves, and until an
    // image taken where it stands has arrived. Standing, an image is asked for once, and again
    // when the base volumes drawn change (`occluderVersion`). `view`: {position, forward}.
    update(view, occluderVersion) {
        const camera = this.world.camera;
        const pose = { position: view.position.slice(), forward: view.forward.slice(), fov: camera.fov, aspect: camera.aspect };
        const standing = this.lastPose !== null && samePose(this.lastPose, pose);
        this.lastPose = pose;
        this.arrived = false;
        if (!standing) return null;
        const t = this.taken;
        if (!this.pending && !(t && t.occluderVersion === occluderVersion && samePose(t.pose, pose))) {
            this.taken = { pose, occluderVersion };
            this.take(camera, pose);
        }
        return this.snapshot && samePose(this.snapshotPose, pose) ? this.snapshot : null;
    }

    // Draws the base volumes for `camera`, standing at `pose`, and reads them back without
    // waiting; the image becomes the snapshot once it arrives.
    take(camera, pose) {
        const { renderer, scene } = this.world;
        const size = renderer.getDrawingBufferSize(new THREE.Vector2());
        const width = Math.max(1, Math.ceil(size.x / 2)), height = Math.max(1, Math.ceil(size.y / 2));
        if (this.target.width !== width || this.target.height !== height) this.target.setSize(width, height);
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
        const pixels = new Uint8Array(4 * width * height);
        const reading = renderer.readRenderTargetPixelsAsync(this.target, 0, 0, width, height, pixels);
        renderer.setRenderTarget(saved.target);
        renderer.setClearColor(clear, clearAlpha);
        Object.assign(scene, { background: saved.background, fog: saved.fog, overrideMaterial: saved.override });

        const far = camera.far;
        const e = camera.matrixWorldInverse.elements, p = camera.projectionMatrix.elements;
        const frame = { rotation: [e[0], e[1], e[2], e[4], e[5], e[6], e[8], e[9], e[10]], scaleX: p[0], scaleY: p[5], near: camera.near };
        this.pending = true;
        reading
            .then(() => {
                const depths = new Float32Array(width * height);
                for (let i = 0; i < width * height; ++i) {
                    const v = pixels[4 * i] * 65536 + pixels[4 * i + 1] * 256 + pixels[4 * i + 2];
                    depths[i] = v >= 16777215 ? Infinity : (v / 16777215) * far;
                }
                this.snapshot = new OcclusionTiles(farthestPerTile(depths, width, height, TILE_PIXELS), frame, ++this.version, SLACK);
                this.snapshotPose = pose;
                this.arrived = true;
            })
            // A lost read (a lost context) leaves the last image; the next move asks again.
            .catch(() => {})
            .finally(() => (this.pending = false));
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
