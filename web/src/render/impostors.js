// LOD3 and LOD2 of terminals whose shape has a baked impostor (scene.capabilities.impostors;
// the atlases of /api/v1/impostors/...: albedo PNG, sRGB with coverage in alpha, and the
// shape-space normal with depth PNG). An impostor is a quad in the frame of the shape's bounding
// sphere (centre, radius, shape space at the nominal size) carried by the terminal's matrix (one
// merged mesh of quads per shape and LOD, impostor_quads.js). LOD2 is the central view on the
// rectangle of the mesh's bounds on the wall plane (z = 0), as the native renderer draws it: the
// sphere's square would shade twice the fragments, and a software rasteriser pays for every
// one of them. LOD3 faces the camera and blends up to four views around the camera's direction
// in shape space with the native renderer's weights (view_table.js), each sampled where the
// quad's point lies in that view's frame (the reconstruction of
// impostor_views.glsl without its depth iterations). Coverage under one half is discarded
// (alpha test, no sorting); normals light it as the meshes are lit (lights.js).
import * as THREE from 'three';

import { ImpostorQuads, QUAD_MATRIX_GLSL } from './impostor_quads.js';
import { IMPOSTOR_ATLAS_GLSL, IMPOSTOR_VIEWS_GLSL } from './impostor_views.js';
import { FACADE_TABLE_RESOLUTION, layoutTableUniforms, VIEW_TABLE_GLSL } from './view_table.js';
import { LIGHTING_GLSL, lightingUniforms } from './lights.js';

const VERTEX = /* glsl */ `
uniform vec3 nominal;
uniform vec4 sphere;       // centre xyz, radius (shape space)
uniform vec2 wallMin, wallMax; // LOD2's rectangle on the wall plane: the mesh's bounds (shape space)
uniform vec4 atlasLayout;       // grid, view resolution, padding, central view
uniform float lod;         // 2 or 3
uniform vec3 sunDirection; // world
flat out vec4 vViews;
out vec4 vWeights;
out vec2 vUv0, vUv1, vUv2, vUv3;
out vec3 vSun;             // the sun in shape space
out vec3 vUp;              // world up in shape space
${QUAD_MATRIX_GLSL}
${IMPOSTOR_VIEWS_GLSL}
${VIEW_TABLE_GLSL}
vec2 viewUv(float view, vec3 q) {
    vec3 right, up;
    impostorBasis(impostorViewDirection(view, atlasLayout.x), right, up);
    return vec2(dot(q, right), dot(q, up));
}
// Shape space (metres at the nominal size) to world. A flat shape (nominal depth 0, the wall
// tile) or a terminal of depth 0 has no depth scale of its own: its z stays metres along the
// facade normal, as the renderer's normal rule takes a zero nominal component as a ratio of 1.
// Dividing by the zero depth instead would make the matrix singular and its inverse NaN.
mat4 shapeToWorldMatrix() {
    mat4 terminal = quadMatrix();
    vec3 x = terminal[0].xyz / nominal.x, y = terminal[1].xyz / nominal.y;
    vec3 z = terminal[2].xyz;
    z = nominal.z > 1e-6 && dot(z, z) > 1e-12 ? z / nominal.z : normalize(cross(x, y));
    return modelMatrix * mat4(vec4(x, 0.0), vec4(y, 0.0), vec4(z, 0.0), terminal[3]);
}
void main() {
    mat4 shapeToWorld = shapeToWorldMatrix();
    mat3 linear = mat3(shapeToWorld);
    mat3 worldToShape = inverse(linear);
    vec3 centre = (shapeToWorld * vec4(sphere.xyz, 1.0)).xyz;
    vec3 toCamera = normalize(worldToShape * (cameraPosition - centre));
    vec3 q; // the quad's point in radii, relative to the centre
    if (lod < 2.5) {
        vViews = vec4(atlasLayout.w, atlasLayout.w, atlasLayout.w, atlasLayout.w);
        vWeights = vec4(1.0, 0.0, 0.0, 0.0);
        // The view projects orthographically, so a point of the wall plane samples the texel
        // the view shows there.
        q = (vec3(mix(wallMin, wallMax, 0.5 * position.xy + 0.5), 0.0) - sphere.xyz) / sphere.w;
    } else {
        tableBlend(impostorTablePosition(toCamera), vViews, vWeights);
        vec3 forward = toCamera;
        forward.z = max(forward.z, 0.0);
        forward = normalize(forward + vec3(0.0, 0.0, 1e-6));
        vec3 right, up;
        impostorBasis(forward, right, up);
        q = position.x * right + position.y * up;
    }
    vUv0 = viewUv(vViews.x, q);
    vUv1 = viewUv(vViews.y, q);
    vUv2 = viewUv(vViews.z, q);
    vUv3 = viewUv(vViews.w, q);
    vSun = normalize(worldToShape * sunDirection);
    vUp = normalize(worldToShape * vec3(0.0, 0.0, 1.0));
    gl_Position = projectionMatrix * viewMatrix * shapeToWorld * vec4(sphere.xyz + sphere.w * q, 1.0);
}
`;

const FRAGMENT = /* glsl */ `
uniform sampler2D albedoAtlas;
uniform sampler2D normalAtlas;
uniform vec4 atlasLayout;
flat in vec4 vViews;
in vec4 vWeights;
in vec2 vUv0, vUv1, vUv2, vUv3;
in vec3 vSun, vUp;
${IMPOSTOR_ATLAS_GLSL}
${LIGHTING_GLSL}
void main() {
    vec4 colour, normalDepth;
    accumulateViews(albedoAtlas, normalAtlas, atlasLayout.xyz, vViews, vWeights, vUv0, vUv1, vUv2, vUv3, colour,
                    normalDepth);
    if (colour.a < 0.5) discard;
    vec3 albedo = colour.rgb / colour.a;
    vec3 n = length(normalDepth.xyz) > 0.0 ? normalize(normalDepth.xyz) : vec3(0.0, 0.0, 1.0);
    gl_FragColor = vec4(albedo * lambertLight(n, vSun, vUp), 1.0);
    #include <colorspace_fragment>
}
`;

// An atlas PNG as a texture. `colour`: the albedo, sRGB and premultiplied by its coverage on
// upload, so that filtering between a covered texel and an empty one fades the coverage, not
// the colour toward the empty texel's; else data (normal and depth), taken as stored.
export function loadTexture(loader, url, colour) {
    return loader.loadAsync(url).then((texture) => {
        texture.flipY = false; // row 0 of the image is the top row of the atlas, as in the bake
        texture.generateMipmaps = false; // mips would bleed between tiles
        texture.minFilter = THREE.LinearFilter;
        texture.magFilter = THREE.LinearFilter;
        texture.colorSpace = colour ? THREE.SRGBColorSpace : THREE.NoColorSpace;
        texture.premultiplyAlpha = colour;
        texture.needsUpdate = true;
        return texture;
    });
}

// LOD2's rectangle (uniforms wallMin, wallMax): the x, y extent of the mesh's bounds, or the
// sphere's square where a service gives no bounds.
function wallRectangle(impostor) {
    const [cx, cy] = impostor.centre, r = impostor.radius;
    const min = impostor.bounds_min ?? [cx - r, cy - r], max = impostor.bounds_max ?? [cx + r, cy + r];
    return { wallMin: { value: new THREE.Vector2(min[0], min[1]) }, wallMax: { value: new THREE.Vector2(max[0], max[1]) } };
}

export class ImpostorSet {
    constructor(scene, lighting) {
        this.layout = scene.impostor_layout ?? null;
        this.lighting = lighting;
        this.atlases = new Map(); // "grammar/shape" -> atlas
        this.failed = [];
        this.enabled = !!scene.capabilities?.impostors && this.layout?.sphere === 'hemi-octahedral';
        // One table for every facade: they share the layout.
        this.table = this.enabled ? layoutTableUniforms(this.layout, FACADE_TABLE_RESOLUTION, this.failed) : null;
        this.enabled &&= !!this.table;
        this.isReady = false;
        this.ready = (this.enabled ? this.load(scene) : Promise.resolve()).then(() => (this.isReady = true));
    }

    async load(scene) {
        const loader = new THREE.TextureLoader();
        const jobs = [];
        for (const grammar of scene.grammars) {
            for (const [i, shape] of (grammar.shapes ?? []).entries()) {
                const imp = shape.impostor;
                if (!imp?.albedo_url || !imp?.normal_url) continue;
                const index = shape.index ?? shape.id ?? i;
                const nominal = shape.nominal_size ?? [shape.width, shape.height, shape.depth];
                jobs.push(
                    Promise.all([loadTexture(loader, imp.albedo_url, true), loadTexture(loader, imp.normal_url, false)]).then(
                        ([albedo, normal]) => this.atlases.set(`${grammar.index}/${index}`, { albedo, normal, nominal, impostor: imp, materials: {} }),
                        (e) => this.failed.push(`${shape.name}: ${e?.message ?? 'could not load its atlas'}`),
                    ),
                );
            }
        }
        await Promise.all(jobs);
    }

    atlasOf(grammar, shape) {
        return this.enabled ? this.atlases.get(`${grammar}/${shape}`) ?? null : null;
    }

    material(atlas, lod) {
        if (atlas.materials[lod]) return atlas.materials[lod];
        const { grid, view_resolution, padding, central_view } = this.layout;
        const imp = atlas.impostor;
        const material = new THREE.ShaderMaterial({
            // three.js compiles it as GLSL ES 3.00 (WebGL 2): flat varyings and inverse() exist.
            vertexShader: VERTEX,
            fragmentShader: FRAGMENT,
            uniforms: {
                nominal: { value: new THREE.Vector3(...atlas.nominal) },
                sphere: { value: new THREE.Vector4(...imp.centre, imp.radius) },
                ...wallRectangle(imp),
                atlasLayout: { value: new THREE.Vector4(grid, view_resolution, padding, central_view) },
                lod: { value: lod },
                ...this.table,
                albedoAtlas: { value: atlas.albedo },
                normalAtlas: { value: atlas.normal },
                sunDirection: { value: this.lighting.sunDirection },
                ...lightingUniforms(this.lighting),
            },
        });
        atlas.materials[lod] = material;
        return material;
    }

    // Quads for up to `capacity` terminals, written as an InstancedMesh's instances are.
    makeMesh(atlas, lod, capacity) {
        const mesh = new ImpostorQuads(this.material(atlas, lod), capacity);
        mesh.raycast = () => {}; // picking hits the base volumes behind impostors
        return mesh;
    }

    get status() {
        if (!this.enabled) return this.failed.length ? `off: ${this.failed[0]}` : 'off';
        const failed = this.failed.length ? `, ${this.failed.length} failed` : '';
        return `${this.atlases.size} atlases${failed}`;
    }
}
