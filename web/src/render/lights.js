// The viewer's lights, and the same lighting for the shaders that do not use three.js's lights
// (impostors, tree billboards, the ground): a sun plus a sky hemisphere about world up (+z).
// Meshes are MeshLambertMaterial lit by the three.js lights; the impostor shaders light their
// baked normals with lambertLight, so an impostor and the mesh it stands for match across an
// LOD switch on every facing: three.js's Lambert divides light by pi, and its hemisphere light
// gives a normal n the mix of its ground and sky colours by 0.5 * dot(n, up) + 0.5.
import * as THREE from 'three';

export const WORLD_UP = new THREE.Vector3(0, 0, 1);

// {lights: the three.js lights to add to the scene, lighting: the terms the shaders take}.
export function makeLights() {
    const sunDirection = new THREE.Vector3(0.45, -0.35, 0.82).normalize();
    const sun = new THREE.DirectionalLight(new THREE.Color(1.0, 0.96, 0.9), 2.2);
    sun.position.copy(sunDirection);
    const sky = new THREE.HemisphereLight(0xc8d8ff, 0x6a6255, 1.4);
    // three.js aims a hemisphere light along its own default up, +y; the viewer's world is
    // z-up. Left at +y it lit north facades with the sky and south ones with the ground.
    sky.position.copy(WORLD_UP);
    const perPi = (colour, intensity) => colour.clone().multiplyScalar(intensity / Math.PI);
    const lighting = {
        sunDirection,
        sunColour: perPi(sun.color, sun.intensity),
        skyColour: perPi(sky.color, sky.intensity),
        groundColour: perPi(sky.groundColor, sky.intensity),
    };
    return { lights: [sun, sky], lighting };
}

// The light (per unit albedo) a Lambert surface of unit world normal `normal` receives.
export function lambertLight(lighting, normal) {
    const ambient = lighting.groundColour.clone().lerp(lighting.skyColour, 0.5 * normal.dot(WORLD_UP) + 0.5);
    return lighting.sunColour.clone().multiplyScalar(Math.max(normal.dot(lighting.sunDirection), 0)).add(ambient);
}

// The uniforms LIGHTING_GLSL declares.
export function lightingUniforms(lighting) {
    return {
        sunColour: { value: lighting.sunColour },
        skyColour: { value: lighting.skyColour },
        groundColour: { value: lighting.groundColour },
    };
}

// lambertLight in GLSL: n, sun (toward the sun) and up unit vectors of one frame.
export const LIGHTING_GLSL = /* glsl */ `
uniform vec3 sunColour;
uniform vec3 skyColour;
uniform vec3 groundColour;
vec3 lambertLight(vec3 n, vec3 sun, vec3 up) {
    return mix(groundColour, skyColour, 0.5 * dot(n, up) + 0.5) + sunColour * max(dot(n, sun), 0.0);
}
`;
