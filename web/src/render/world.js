// The three.js side of the viewer: renderer, lights, ground and one group per cell, rendered
// camera-relative (ARCHITECTURE.md §6). The three.js camera stays at the origin; each frame
// every cell group is placed at its origin minus the camera position, computed in JavaScript
// doubles, so float32 only ever holds offsets of a few kilometres, however far from the world
// origin the city lies. Coordinates are z-up metres.
import * as THREE from 'three';

import { Ground } from './ground.js';
import { makeLights } from './lights.js';

export class World {
    constructor(canvas, { antialias = true } = {}) {
        this.renderer = new THREE.WebGLRenderer({ canvas, antialias, preserveDrawingBuffer: true });
        this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
        this.scene = new THREE.Scene();
        this.scene.background = new THREE.Color(0.62, 0.74, 0.88);
        this.scene.fog = new THREE.Fog(this.scene.background, 2500, 9000);
        this.camera = new THREE.PerspectiveCamera(60, 1, 0.5, 20000);
        this.camera.up.set(0, 0, 1);
        const { lights, lighting } = makeLights();
        this.scene.add(...lights);
        this.lighting = lighting; // for the shaders that light without three.js's lights
        this.groundPlane = new Ground(new THREE.Color(0.3, 0.32, 0.28), this.lighting);
        this.ground = this.groundPlane.mesh; // what picking hits
        this.scene.add(this.ground);
        this.groundZ = 0;
        this.cells = new Map(); // "q,r" -> {group, origin}
        this.cameraPosition = [0, 0, 0];
    }

    cellGroup(cell) {
        const id = `${cell.q},${cell.r}`;
        let entry = this.cells.get(id);
        if (!entry) {
            entry = { group: new THREE.Group(), origin: cell.origin };
            entry.group.name = `cell ${id}`;
            entry.group.userData.cell = cell;
            this.cells.set(id, entry);
            this.scene.add(entry.group);
        }
        return entry.group;
    }

    resize(width, height) {
        this.renderer.setSize(width, height, false);
        this.camera.aspect = width / height;
        this.camera.updateProjectionMatrix();
    }

    // `view`: {position: [x, y, z] doubles, forward: [x, y, z], near, fovY}. Places the camera and
    // every cell group for it (the streamer's frustum test needs the camera before a frame).
    place(view) {
        const [cx, cy, cz] = view.position;
        this.cameraPosition = view.position;
        this.camera.position.set(0, 0, 0);
        this.camera.near = view.near;
        this.camera.fov = (view.fovY * 180) / Math.PI;
        this.camera.updateProjectionMatrix();
        this.camera.lookAt(view.forward[0], view.forward[1], view.forward[2]);
        for (const { group, origin } of this.cells.values())
            group.position.set(origin[0] - cx, origin[1] - cy, origin[2] - cz);
        this.groundPlane.height = this.groundZ - cz - 0.02;
        this.camera.updateMatrixWorld();
    }

    render(view) {
        this.place(view);
        this.renderer.render(this.scene, this.camera);
    }
}
