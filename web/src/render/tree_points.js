// Far trees as points, as the native renderer draws them (lod/shaders/tree_point.vert, thesis
// §7.4): a tree whose species sphere spans fewer pixels than the point size shows no more
// than an average colour, so it is one point of its species' mean albedo and coverage for the
// view nearest the direction to the camera (tree_view_averages.js), lit by that view's mean
// normal, its area the area the tree covers, instead of a billboard whose fragments each
// blend up to four atlas views. Software renderers pay per fragment and per vertex: a city's
// far trees are hundreds of thousands of billboards a few pixels across.
//
// Which trees are points is the cut's (tree_billboards.js): treeIsPoint decides per tree, on
// the CPU, so a tree is exactly one of billboard and point. TreePoints holds one batch's
// points, of every species, in one draw; the species' spheres and view averages are rows of
// one table that every batch's points share (TreePointMaterial).
import * as THREE from 'three';

import { COVERAGE_HASH_GLSL, POINT_FRAGMENT } from './far_points.js';
import { geometryBytes } from './geometry_bytes.js';
import { TREE_VIEWS_GLSL } from './impostor_views.js';
import { LIGHTING_GLSL, lightingUniforms } from './lights.js';
import { VIEW_TABLE_GLSL } from './view_table.js';

// How many times the error bound a tree's sphere may span on screen and still be a point: the
// native `treePointsUnderSse`.
export const TREE_POINTS_UNDER_SSE = 2;

// Whether a tree whose species sphere has radius `radius` and whose centre is `distance` from
// the camera is a point, for `pointDistancePerMetre` (pointDistancePerMetre below; 0: never).
export function treeIsPoint(radius, distance, pointDistancePerMetre) {
    return pointDistancePerMetre > 0 && 2 * radius * pointDistancePerMetre < distance;
}

// The distance, per metre of sphere diameter, beyond which a tree is a point: a diameter d
// spans d * scale / distance pixels (`scale`: lod_policy.screenScale), under
// TREE_POINTS_UNDER_SSE * maxScreenSpaceError past d * this.
export function pointDistancePerMetre(scale, maxScreenSpaceError) {
    return scale / (TREE_POINTS_UNDER_SSE * maxScreenSpaceError);
}

const VERTEX = /* glsl */ `
attribute float species;     // the tree's species: its row of the table
uniform sampler2D speciesTable; // per species: sphere (centre, radius), then per view albedo and coverage, normal
uniform float screenScale;   // pixels one metre spans at one metre's distance
uniform vec3 sunDirection;
uniform bool multisampled;   // the billboards' coverage is alpha to coverage, not a cutout
flat out vec3 vColour;
${TREE_VIEWS_GLSL}
${VIEW_TABLE_GLSL}
${LIGHTING_GLSL}
${COVERAGE_HASH_GLSL}
#include <fog_pars_vertex>
void main() {
    vec3 centre = (modelMatrix * vec4(position, 1.0)).xyz; // the sphere's centre, camera-relative (world.js)
    int row = int(species + 0.5);
    vec4 sphere = texelFetch(speciesTable, ivec2(0, row), 0);
    float distance = max(length(centre), 1e-3);
    vec3 toCamera = -centre / distance;
    vec4 views, weights;
    tableBlend(treeTablePosition(toCamera), views, weights);
    int view = int(views.x + 0.5); // the view that weighs most
    vec4 albedo = texelFetch(speciesTable, ivec2(1 + 2 * view, row), 0);
    vec4 normal = texelFetch(speciesTable, ivec2(2 + 2 * view, row), 0);
    // The sphere's diameter on screen, shrunk to the area the tree covers in it: its billboard's
    // coverage, or the texels its cutout keeps.
    float covered = multisampled ? albedo.a : normal.w;
    float side = 2.0 * sphere.w * screenScale / distance * sqrt(covered);
    gl_PointSize = max(side, 1.0);
    if (side < 1.0 && coverageHash(position) >= side * side) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume
        return;
    }
    // Tree space is world space turned by nothing: its normals are world normals. The mean
    // normal is not made unit: the sky's light is linear in the normal, so the mean normal
    // gives the view's mean exactly, and a unit one would light a canopy whose normals spread
    // as if they all faced one way (brighter than its billboard by about a sixth).
    vColour = albedo.rgb * lambertLight(normal.xyz, sunDirection, vec3(0.0, 0.0, 1.0));
    vec4 mvPosition = viewMatrix * vec4(centre, 1.0);
    gl_Position = projectionMatrix * mvPosition;
    #include <fog_vertex>
}
`;

// The one material every batch's tree points share, with the table of the species that have
// view averages. `table`: the tree view table's uniforms (view_table.js layoutTableUniforms);
// `multisampled`: whether the billboards the points stand for cover by alpha to coverage
// (tree_impostors.js), else by a cutout at one half.
export class TreePointMaterial extends THREE.ShaderMaterial {
    constructor(table, lighting, multisampled) {
        super({
            vertexShader: VERTEX,
            fragmentShader: POINT_FRAGMENT,
            fog: true,
            uniforms: {
                ...THREE.UniformsUtils.clone(THREE.UniformsLib.fog),
                ...table, // shared with the billboards, not copied
                speciesTable: { value: null },
                screenScale: { value: 1 },
                multisampled: { value: multisampled },
                sunDirection: { value: lighting.sunDirection },
                ...lightingUniforms(lighting),
            },
        });
    }

    // The table from `species` (by index: {impostor: {centre, radius}, averages}, or empty
    // where an index has no species): row i is species i's sphere, then its views' averages.
    setSpecies(species) {
        // for...of, not map: species indices come as the service numbers them, with holes
        // (a retired species), which map would skip and Math.max read as NaN.
        let views = 0;
        for (const s of species) views = Math.max(views, (s?.averages?.length ?? 0) / 8);
        const width = 1 + 2 * views, height = Math.max(species.length, 1);
        const data = new Float32Array(4 * width * height);
        species.forEach((s, row) => {
            if (!s?.averages) return;
            data.set([...s.impostor.centre, s.impostor.radius], 4 * width * row);
            data.set(s.averages, 4 * (width * row + 1));
        });
        const texture = new THREE.DataTexture(data, width, height, THREE.RGBAFormat, THREE.FloatType);
        texture.minFilter = texture.magFilter = THREE.NearestFilter;
        texture.needsUpdate = true;
        this.uniforms.speciesTable.value?.dispose();
        this.uniforms.speciesTable.value = texture;
    }
}

// One batch's far trees drawn as points: room for `capacity`, none drawn until `show`.
export class TreePoints extends THREE.Points {
    constructor(material, capacity) {
        const geometry = new THREE.BufferGeometry();
        for (const [name, size] of [['position', 3], ['species', 1]]) {
            const attribute = new THREE.BufferAttribute(new Float32Array(size * capacity), size);
            attribute.setUsage(THREE.DynamicDrawUsage);
            geometry.setAttribute(name, attribute);
        }
        // Points move with the cut: bounds would go stale, and the cell group's place suffices.
        geometry.boundingSphere = new THREE.Sphere(new THREE.Vector3(), Infinity);
        super(geometry, material);
        this.frustumCulled = false;
        this.raycast = () => {}; // a click on a far tree selects the ground's cell
        this.capacity = capacity;
        this.show(0);
    }

    // Places point `slot` at x, y, z (cell-local: the tree's sphere centre), of species `s`.
    place(slot, x, y, z, s) {
        this.geometry.attributes.position.array.set([x, y, z], 3 * slot);
        this.geometry.attributes.species.array[slot] = s;
    }

    // Draws the first `count` points placed, and uploads them.
    show(count) {
        this.count = count;
        this.geometry.setDrawRange(0, count);
        this.visible = count > 0;
        this.geometry.attributes.position.needsUpdate = true;
        this.geometry.attributes.species.needsUpdate = true;
    }

    // Bytes held for the GPU.
    get bytes() {
        return geometryBytes(this.geometry);
    }

    dispose() {
        this.geometry.dispose();
    }
}
