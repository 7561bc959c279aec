// The billboards of one tree batch, from its extruded set: each tree stands at the centre of
// its footprint on its base elevation (as lod/tree_pass.cpp places it) and is drawn with the
// impostor of its species, found by its exact parameter values. A tree whose values match no
// served species (it was edited since the service baked them) has no billboard: `unmatched`
// counts them, and the streamer then draws the batch from its terminals instead.
import * as THREE from 'three';

export class TreeBillboards {
    // `set`: a decoded extruded set of a tree grammar; `species`: a TreeImpostors.
    constructor(set, species) {
        this.group = new THREE.Group();
        this.group.name = `trees ${set.cell.q},${set.cell.r}/${set.grammar}`;
        const { buildings, footprints } = set;
        const values = new Float32Array(set.parametersPerBuilding);
        const bySpecies = new Map(); // species index -> [x, y, z, ...]
        this.unmatched = 0;
        for (let i = 0; i < buildings.count; ++i) {
            for (let j = 0; j < values.length; ++j) values[j] = set.parameters[j][i];
            const s = species.speciesOf(set.grammar, values);
            if (s < 0) {
                ++this.unmatched;
                continue;
            }
            let x = 0, y = 0;
            const first = buildings.firstVertex[i], n = buildings.vertexCount[i];
            for (let v = first; v < first + n; ++v) {
                x += footprints.x[v];
                y += footprints.y[v];
            }
            if (!bySpecies.has(s)) bySpecies.set(s, []);
            bySpecies.get(s).push(x / Math.max(n, 1), y / Math.max(n, 1), buildings.baseElevation[i]);
        }
        this.count = buildings.count - this.unmatched;
        for (const [s, bases] of bySpecies) this.group.add(species.makeMesh(s, Float32Array.from(bases)));
        this.gpuBytes = 64 * this.count;
    }

    dispose() {
        for (const mesh of this.group.children) mesh.dispose();
    }
}
