// The tree species' full-sphere impostors (scene.tree_species, scene.tree_impostor_layout; the
// files of /api/v1/tree-impostors/...), drawn as billboards for trees far from the camera, as
// the native renderer does (thesis §7.4). A billboard is a camera-facing quad in the plane
// through the centre of the species' bounding sphere (centre, radius: tree space, x east, y
// north, z up, the trunk base at the origin), over what the camera sees of the species' box
// within the sphere's square, as lod/shaders/tree_billboard.vert places it: the square's other
// pixels show nothing. It blends up to four views around the direction to the camera with the
// native renderer's weights (view_table.js), each sampled where the quad's point lies in that
// view's frame. It writes the depth the views store, so a billboard sinks into the ground and
// behind buildings where the tree does, not where its flat quad would. As in the native
// renderer, coverage becomes the sample mask on a multisampled canvas (alpha to coverage) and is
// a cutout at one half otherwise; the stored normals light it as the meshes are lit (lights.js).
// A far tree small on screen is a point instead (tree_points.js), of its species' view
// averages, which are computed here as the atlases load (tree_view_averages.js).
import * as THREE from 'three';

import { loadTexture } from './impostors.js';
import { FULL_SPHERE, IMPOSTOR_ATLAS_GLSL, TREE_VIEWS_GLSL } from './impostor_views.js';
import { layoutTableUniforms, SPECIES_TABLE_RESOLUTION, VIEW_TABLE_GLSL } from './view_table.js';
import { LIGHTING_GLSL, lightingUniforms } from './lights.js';
import { TreePointMaterial, TreePoints } from './tree_points.js';
import { TreeQuads } from './tree_quads.js';
import { imagePixels, treeViewAverages } from './tree_view_averages.js';

const VERTEX = /* glsl */ `
uniform vec4 sphere;      // centre xyz, radius (tree space)
uniform vec3 boxLo, boxHi; // the species' box (tree space); the sphere's cube draws the square
uniform vec3 atlasLayout; // grid, view resolution, padding
in vec3 treeBase;         // the tree's trunk base (cell-local), tree_quads.js
flat out vec4 vViews;
out vec4 vWeights;
out vec2 vUv0, vUv1, vUv2, vUv3;
// Clip position of the quad point and of one radius toward the camera: the point a view's
// depth d stands for is at vClip + d * vClipForward (clip space is linear in the position).
out vec4 vClip, vClipForward;
${TREE_VIEWS_GLSL}
${VIEW_TABLE_GLSL}
#include <fog_pars_vertex>
vec2 viewUv(float view, vec3 q) {
    vec3 right, up;
    treeBasis(treeViewDirection(view, atlasLayout.x), right, up);
    return vec2(dot(q, right), dot(q, up));
}
// The rectangle, in radii from the centre along right and up, of the box's corners taken
// along their rays from the camera onto the quad's plane, within the square; the square where
// a corner is not in front of the camera's side of the plane.
void boxRectangle(vec3 base, vec3 centre, vec3 right, vec3 up, out vec2 lo, out vec2 hi) {
    vec3 toCentre = centre - cameraPosition;
    vec3 ray = normalize(toCentre);
    float plane = dot(toCentre, ray);
    lo = vec2(1.0), hi = vec2(-1.0);
    for (int c = 0; c < 8; ++c) {
        vec3 corner = base + mix(boxLo, boxHi, vec3(float(c & 1), float((c >> 1) & 1), float(c >> 2))) - cameraPosition;
        float along = dot(corner, ray);
        if (along <= 1e-3 * plane) {
            lo = vec2(-1.0), hi = vec2(1.0);
            return;
        }
        vec3 offset = corner * (plane / along) - toCentre;
        vec2 at = vec2(dot(offset, right), dot(offset, up)) / sphere.w;
        lo = min(lo, at), hi = max(hi, at);
    }
    lo = max(lo, vec2(-1.0)), hi = min(hi, vec2(1.0));
}
void main() {
    vec3 base = (modelMatrix * vec4(treeBase, 1.0)).xyz;
    vec3 centre = base + sphere.xyz;
    vec3 forward = cameraPosition - centre;
    forward = dot(forward, forward) > 1e-12 ? normalize(forward) : vec3(0.0, 0.0, 1.0);
    tableBlend(treeTablePosition(forward), vViews, vWeights);
    vec3 right, up;
    treeBasis(forward, right, up);
    vec2 lo, hi;
    boxRectangle(base, centre, right, up, lo, hi);
    vec2 at = mix(lo, hi, position.xy * 0.5 + 0.5);
    vec3 q = at.x * right + at.y * up; // in radii, relative to the centre
    vUv0 = viewUv(vViews.x, q);
    vUv1 = viewUv(vViews.y, q);
    vUv2 = viewUv(vViews.z, q);
    vUv3 = viewUv(vViews.w, q);
    mat4 toClip = projectionMatrix * viewMatrix;
    vClip = toClip * vec4(centre + sphere.w * q, 1.0);
    vClipForward = toClip * vec4(sphere.w * forward, 0.0);
    gl_Position = vClip;
    vec4 mvPosition = viewMatrix * vec4(centre + sphere.w * q, 1.0);
    #include <fog_vertex>
}
`;

const FRAGMENT = /* glsl */ `
uniform sampler2D albedoAtlas;
uniform sampler2D normalAtlas;
uniform vec3 atlasLayout;
uniform vec3 sunDirection;
uniform float cutout;
flat in vec4 vViews;
in vec4 vWeights;
in vec2 vUv0, vUv1, vUv2, vUv3;
in vec4 vClip, vClipForward;
${IMPOSTOR_ATLAS_GLSL}
${LIGHTING_GLSL}
#include <fog_pars_fragment>
void main() {
    vec4 colour, normalDepth;
    accumulateViews(albedoAtlas, normalAtlas, atlasLayout, vViews, vWeights, vUv0, vUv1, vUv2, vUv3, colour, normalDepth);
    if (colour.a < cutout) discard;
    vec3 albedo = colour.rgb / colour.a;
    vec3 n = length(normalDepth.xyz) > 0.0 ? normalize(normalDepth.xyz) : vec3(0.0, 0.0, 1.0);
    vec4 clip = vClip + (normalDepth.w / colour.a) * vClipForward;
    gl_FragDepth = clamp(0.5 * clip.z / clip.w + 0.5, 0.0, 1.0);
    // Tree space is world space turned by nothing: its normals are world normals.
    gl_FragColor = vec4(albedo * lambertLight(n, sunDirection, vec3(0.0, 0.0, 1.0)), min(colour.a, 1.0));
    #include <colorspace_fragment>
    #include <fog_fragment>
}
`;

// A species' key: its tree grammar and the exact float bits of its parameters.
function speciesKey(grammar, parameters) {
    return `${grammar}:${Array.from(new Uint32Array(Float32Array.from(parameters).buffer)).join(',')}`;
}

export class TreeImpostors {
    // `multisampled`: whether the canvas has samples for alpha to coverage.
    // `boxes`: each billboard covers its species' box alone (false: the sphere's whole square,
    // for comparisons). `points`: far trees small on screen are points (false: billboards).
    constructor(scene, lighting, { multisampled = true, boxes = true, points = true } = {}) {
        this.layout = scene.tree_impostor_layout ?? null;
        this.lighting = lighting;
        this.multisampled = multisampled;
        this.boxes = boxes;
        this.pointsAllowed = points;
        this.species = []; // by species index: {albedo, normal, impostor, material, averages}
        this.byKey = new Map();
        this.failed = [];
        this.withoutPoints = []; // species whose view averages could not be read, and why
        this.enabled = !!scene.capabilities?.tree_billboards && this.layout?.sphere === FULL_SPHERE;
        this.table = this.enabled ? layoutTableUniforms(this.layout, SPECIES_TABLE_RESOLUTION, this.failed) : null;
        this.enabled &&= !!this.table;
        this.generation = 0; // grows with every species added after the start
        this.adding = new Set(); // species indices being loaded by add()
        this.pointMaterial = null; // the far trees' points' material, once a batch has points
        this.isReady = false;
        this.ready = (this.enabled ? this.load(scene.tree_species ?? []) : Promise.resolve()).then(() => (this.isReady = true));
    }

    async load(list) {
        const loader = new THREE.TextureLoader();
        await Promise.all(
            list.map((s) =>
                Promise.all([loadTexture(loader, s.impostor.albedo_url, true), loadTexture(loader, s.impostor.normal_url, false)]).then(
                    ([albedo, normal]) => {
                        const averages = this.pointsAllowed ? this.viewAverages(albedo, normal, s.name) : null;
                        this.species[s.index] = { albedo, normal, impostor: s.impostor, material: null, averages };
                        this.byKey.set(speciesKey(s.grammar, s.parameters), s.index);
                    },
                    (e) => this.failed.push(`${s.name}: ${e?.message ?? 'could not load its atlas'}`),
                ),
            ),
        );
    }

    // A species the service baked for edited trees (a "species" event, or one listed by the
    // scene after a reconnect), loaded like those of the start. `generation` then grows, so
    // that batches whose trees matched no species match again (TreeBillboards.generation).
    async add(entry) {
        if (!this.enabled || this.species[entry.index] || this.adding.has(entry.index)) return false;
        this.adding.add(entry.index);
        await this.ready;
        await this.load([entry]);
        this.adding.delete(entry.index);
        if (!this.species[entry.index]) return false;
        this.pointMaterial?.setSpecies(this.species);
        ++this.generation;
        return true;
    }

    // The view averages of species `name`'s atlases (tree_view_averages.js), or null where
    // they cannot be read: its far trees are then billboards at any distance.
    viewAverages(albedo, normal, name) {
        try {
            const a = imagePixels(albedo.image), n = imagePixels(normal.image);
            return treeViewAverages(a.data, n.data, a.width, this.layout);
        } catch (e) {
            this.withoutPoints.push(`${name}: ${e?.message ?? e}`);
            return null;
        }
    }

    // Whether the trees of species `index` can be drawn as points.
    hasPoints(index) {
        return this.pointsAllowed && !!this.species[index]?.averages;
    }

    // Room for `capacity` far trees drawn as points (tree_points.js).
    makePoints(capacity) {
        if (!this.pointMaterial) {
            this.pointMaterial = new TreePointMaterial(this.table, this.lighting, this.multisampled);
            this.pointMaterial.setSpecies(this.species);
        }
        return new TreePoints(this.pointMaterial, capacity);
    }

    // The species index of a tree of `grammar` with these parameter values, or -1 (an edited
    // tree whose species is not baked yet, or a species whose atlas failed to load).
    speciesOf(grammar, parameters) {
        return this.byKey.get(speciesKey(grammar, parameters)) ?? -1;
    }

    material(index) {
        const species = this.species[index];
        if (species.material) return species.material;
        const { grid, view_resolution, padding } = this.layout;
        const imp = species.impostor;
        // Without its bounds (or boxes off), the sphere's cube: the quad is the whole square.
        const box = this.boxes && imp.bounds_min && imp.bounds_max
            ? [imp.bounds_min, imp.bounds_max]
            : [imp.centre.map((c) => c - imp.radius), imp.centre.map((c) => c + imp.radius)];
        species.material = new THREE.ShaderMaterial({
            vertexShader: VERTEX,
            fragmentShader: FRAGMENT,
            alphaToCoverage: this.multisampled,
            // The canvas is composited with its alpha (three.js asks for an alpha channel): the
            // coverage that alpha to coverage needs in the fragment's alpha must not reach it, so
            // colour replaces and the cleared alpha of 1 stays.
            blending: THREE.CustomBlending,
            blendEquation: THREE.AddEquation,
            blendSrc: THREE.OneFactor,
            blendDst: THREE.ZeroFactor,
            blendSrcAlpha: THREE.ZeroFactor,
            blendDstAlpha: THREE.OneFactor,
            // Fogged as the meshes, the ground and the far points are: far trees fade with them.
            fog: true,
            uniforms: {
                ...THREE.UniformsUtils.clone(THREE.UniformsLib.fog),
                sphere: { value: new THREE.Vector4(...imp.centre, imp.radius) },
                boxLo: { value: new THREE.Vector3(...box[0]) },
                boxHi: { value: new THREE.Vector3(...box[1]) },
                atlasLayout: { value: new THREE.Vector3(grid, view_resolution, padding) },
                ...this.table,
                albedoAtlas: { value: species.albedo },
                normalAtlas: { value: species.normal },
                sunDirection: { value: this.lighting.sunDirection },
                ...lightingUniforms(this.lighting),
                cutout: { value: this.multisampled ? 0.02 : 0.5 },
            },
        });
        return species.material;
    }

    // Room for `capacity` billboards of species `index` (tree_quads.js).
    makeMesh(index, capacity) {
        const mesh = new TreeQuads(this.material(index), capacity);
        mesh.raycast = () => {}; // a click on a far tree selects the ground's cell
        return mesh;
    }

    get status() {
        if (!this.enabled) return this.failed.length ? `off: ${this.failed[0]}` : 'off';
        const failed = this.failed.length ? `, ${this.failed.length} failed` : '';
        const pointless = this.withoutPoints.length ? `, ${this.withoutPoints.length} without points (${this.withoutPoints[0]})` : '';
        return `${this.byKey.size} species${failed}${pointless}`;
    }
}
