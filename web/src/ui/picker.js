// Picking: a click (without a drag) casts a ray from the camera (at the origin, everything being
// camera-relative) into the scene. A terminal hit names its record's building id, a base volume
// its triangle's building; a tree terminal or the ground selects the cell under the hit
// (cells::HexGrid::cellOf, pointy-top axial). The selected building's base volume is outlined.
import * as THREE from 'three';

// Axial cell of a world point (x, y) on the scene's grid, rounding as cells/src/hex_grid.cpp.
export function cellOf(x, y, grid) {
    const size = grid.size, width = Math.sqrt(3) * size;
    const a = (x - grid.origin[0]) / width, b = (y - grid.origin[1]) / size;
    const q3 = 3 * a - b, r3 = 2 * b, s3 = -3 * a - b;
    const roundHalfUp = (v) => Math.floor(v + 0.5);
    let q = roundHalfUp(q3 / 3), r = roundHalfUp(r3 / 3);
    const s = roundHalfUp(s3 / 3);
    const dq = Math.abs(q3 - 3 * q), dr = Math.abs(r3 - 3 * r), ds = Math.abs(s3 - 3 * s);
    if (dq > dr && dq > ds) q = -r - s;
    else if (dr > ds) r = -q - s;
    return { q: q + 0, r: r + 0 };
}

export class Picker {
    constructor(world, scene) {
        this.world = world;
        this.scene = scene;
        this.raycaster = new THREE.Raycaster();
        this.outline = new THREE.Box3Helper(new THREE.Box3(), 0xffd400);
        this.outline.visible = false;
        this.selectedBox = null; // world box (doubles) of the selected building
    }

    // Client coordinates -> {building, grammar, cell: [q, r], point} or null.
    pick(x, y, canvas) {
        const rect = canvas.getBoundingClientRect();
        const ndc = new THREE.Vector2(((x - rect.left) / rect.width) * 2 - 1, -((y - rect.top) / rect.height) * 2 + 1);
        this.raycaster.setFromCamera(ndc, this.world.camera);
        const targets = [...[...this.world.cells.values()].map((c) => c.group).filter((g) => g.visible), this.world.ground];
        const hits = this.raycaster.intersectObjects(targets, true);
        const c = this.world.cameraPosition;
        for (const hit of hits) {
            const point = [hit.point.x + c[0], hit.point.y + c[1], hit.point.z + c[2]];
            const object = hit.object;
            if (object.userData.batch && hit.instanceId !== undefined) {
                const batch = object.userData.batch;
                const record = batch.recordOf(object, hit.instanceId);
                const grammar = batch.set.grammar;
                const cell = [batch.set.cell.q, batch.set.cell.r];
                if (this.isTree(grammar)) return { grammar, cell, point };
                return { building: batch.buildings[record], grammar, cell, point };
            }
            if (object.userData.buildingOfTriangle && hit.faceIndex !== undefined) {
                const cellData = object.parent?.userData.cell;
                return {
                    building: object.userData.buildingOfTriangle[hit.faceIndex],
                    grammar: object.userData.grammar,
                    cell: cellData ? [cellData.q, cellData.r] : null,
                    point,
                };
            }
            if (object === this.world.ground) {
                const cell = cellOf(point[0], point[1], this.scene.grid ?? { size: this.scene.cell_size, origin: [0, 0] });
                return { cell: [cell.q, cell.r], point };
            }
        }
        return null;
    }

    isTree(grammar) {
        return this.scene.grammars.find((g) => g.index === grammar)?.kind === 'tree';
    }

    // Outlines building `id` from the extruded set drawn for its cell (if any is resident).
    outlineBuilding(id, cellGroup, extruded, origin) {
        this.outline.removeFromParent();
        this.outline.visible = false;
        this.selectedBox = null;
        if (id === undefined || !extruded) return;
        const b = extruded.buildings;
        const i = Array.prototype.indexOf.call(b.id, id);
        if (i < 0) return;
        const box = new THREE.Box3();
        for (let k = 0; k < b.vertexCount[i]; ++k) {
            const v = b.firstVertex[i] + k;
            box.expandByPoint(new THREE.Vector3(extruded.footprints.x[v], extruded.footprints.y[v], b.baseElevation[i]));
        }
        box.max.z = b.baseElevation[i] + b.height[i];
        this.outline.box.copy(box);
        this.outline.visible = true;
        cellGroup.add(this.outline);
        this.selectedBox = {
            min: [box.min.x + origin[0], box.min.y + origin[1], box.min.z + origin[2]],
            max: [box.max.x + origin[0], box.max.y + origin[1], box.max.z + origin[2]],
        };
    }

    // The screen rectangle (CSS pixels) of the selected building's box, for tests and tools.
    screenRect(canvas) {
        if (!this.selectedBox) return null;
        const c = this.world.cameraPosition, rect = canvas.getBoundingClientRect();
        let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
        for (let k = 0; k < 8; ++k) {
            const v = new THREE.Vector3(
                (k & 1 ? this.selectedBox.max : this.selectedBox.min)[0] - c[0],
                (k & 2 ? this.selectedBox.max : this.selectedBox.min)[1] - c[1],
                (k & 4 ? this.selectedBox.max : this.selectedBox.min)[2] - c[2],
            ).project(this.world.camera);
            const x = rect.left + ((v.x + 1) / 2) * rect.width, y = rect.top + ((1 - v.y) / 2) * rect.height;
            x0 = Math.min(x0, x);
            y0 = Math.min(y0, y);
            x1 = Math.max(x1, x);
            y1 = Math.max(y1, y);
        }
        return { x: x0, y: y0, width: x1 - x0, height: y1 - y0 };
    }
}
