// The ground: the plane z = ground height under the whole city, ray-cast per pixel from a
// full-screen quad rather than drawn as geometry. A plane that reaches behind the camera must
// be clipped at the near plane, and SwiftShader did that so badly for a ground of large
// triangles (two of 40 km, or tiles of 300 m to 2.5 km) that at eye level the ground hid the
// bottoms of buildings and trees in some directions, and at viewports under about 400 pixels
// high came out fully fogged (docs/BENCHMARKS.md, "The ground at eye level"). Here each pixel
// intersects its view ray with the plane and writes the hit's own depth, so nothing is
// clipped and the depth is exact. Lit as a Lambert surface facing up (constant over the
// plane), fogged as three.js fogs by view depth; picking hits it as a plane too.
import * as THREE from 'three';

import { lambertLight, WORLD_UP } from './lights.js';

const VERTEX = /* glsl */ `
out vec3 vViewRay;
void main() {
    // The view-space ray through this corner, at view depth 1: linear across the screen.
    vViewRay = vec3(position.x / projectionMatrix[0][0], position.y / projectionMatrix[1][1], -1.0);
    gl_Position = vec4(position.xy, 0.0, 1.0);
}
`;

const FRAGMENT = /* glsl */ `
uniform mat4 projectionMatrix; // three.js declares it for vertex shaders only
uniform float height; // the plane's z minus the camera's (world, z up)
uniform vec3 litColour;
uniform vec3 fogColor;
uniform float fogNear;
uniform float fogFar;
in vec3 vViewRay;
void main() {
    // The ray's world z: viewMatrix turns world directions into view ones, so its third column
    // is the world's up in view space.
    float rayZ = dot(viewMatrix[2].xyz, vViewRay);
    float depth = height / rayZ; // view depth of the hit: the ray has view depth 1 per unit
    // Only rays going down from above it meet it (from under it the plane shows nothing, as a
    // plane's back face culled).
    if (rayZ >= 0.0 || depth <= 0.0) discard;
    vec4 clip = projectionMatrix * vec4(vViewRay * depth, 1.0);
    if (clip.z > clip.w) discard; // beyond the far plane
    gl_FragDepth = 0.5 * clip.z / clip.w + 0.5;
    gl_FragColor = vec4(litColour, 1.0);
    #include <colorspace_fragment>
    gl_FragColor.rgb = mix(gl_FragColor.rgb, fogColor, smoothstep(fogNear, fogFar, depth));
}
`;

export class Ground {
    // `albedo`: linear colour; `lighting`: World's lighting (lights.js), so the ground is lit
    // as a Lambert surface facing up.
    constructor(albedo, lighting) {
        const light = lambertLight(lighting, WORLD_UP);
        this.material = new THREE.ShaderMaterial({
            vertexShader: VERTEX,
            fragmentShader: FRAGMENT,
            fog: true,
            uniforms: THREE.UniformsUtils.merge([
                THREE.UniformsLib.fog,
                { height: { value: 0 }, litColour: { value: albedo.clone().multiply(light) } },
            ]),
        });
        this.mesh = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), this.material);
        this.mesh.name = 'ground';
        this.mesh.frustumCulled = false;
        this.mesh.renderOrder = -1; // first: it writes its depth per pixel, so the GL cannot reject its fragments early
        this.mesh.raycast = (raycaster, intersects) => this.raycast(raycaster, intersects);
    }

    // The plane's height relative to the camera (world z up, camera at the origin).
    set height(value) {
        this.material.uniforms.height.value = value;
    }

    get height() {
        return this.material.uniforms.height.value;
    }

    raycast(raycaster, intersects) {
        const { origin, direction } = raycaster.ray;
        if (direction.z >= 0) return;
        const distance = (this.height - origin.z) / direction.z;
        if (distance < raycaster.near || distance > raycaster.far) return;
        intersects.push({ distance, point: raycaster.ray.at(distance, new THREE.Vector3()), object: this.mesh });
    }
}
