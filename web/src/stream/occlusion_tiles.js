// Occlusion culling for the viewer's terminal lists, after the native renderer's depth tiles
// (lod/include/hexlod/lod/cull_shared.h, occlusionRect): the opaque base volumes are drawn
// alone into a small depth image (render/occluder_depth.js), reduced here to tiles that each
// hold the farthest depth seen anywhere in them, and a terminal's bounding sphere is hidden
// when its nearest point lies behind the farthest depth of every tile its screen rectangle
// covers. Depths are linear view distances in metres; nothing drawn is Infinity.
//
// The depth image has fewer pixels than the canvas, so each of its pixels samples one point
// of a block of canvas pixels. A tile's farthest depth is taken over its pixels and a border
// of one pixel around them, so that a canvas pixel near a silhouette, whose nearest sample
// may lie in the next tile, still counts.

// Tiles of `tilePixels` x `tilePixels` depth-image pixels over a `width` x `height` image of
// linear depths (row 0 at the bottom, as the GL reads it).
export function farthestPerTile(depths, width, height, tilePixels) {
    const columns = Math.ceil(width / tilePixels), rows = Math.ceil(height / tilePixels);
    const tiles = new Float32Array(columns * rows);
    for (let ty = 0; ty < rows; ++ty) {
        const y0 = Math.max(0, ty * tilePixels - 1), y1 = Math.min(height, (ty + 1) * tilePixels + 1);
        for (let tx = 0; tx < columns; ++tx) {
            const x0 = Math.max(0, tx * tilePixels - 1), x1 = Math.min(width, (tx + 1) * tilePixels + 1);
            let farthest = 0;
            for (let y = y0; y < y1 && farthest !== Infinity; ++y)
                for (let x = x0; x < x1; ++x) if (depths[y * width + x] > farthest) farthest = depths[y * width + x];
            tiles[ty * columns + tx] = farthest;
        }
    }
    return { tiles, columns, rows, width, height, tilePixels };
}

// A sphere covering more tiles than this is never tested: near the camera it is rarely
// hidden, and the test would cost more than drawing it.
export const MAX_TILES = 64;

export class OcclusionTiles {
    // `tiles`: farthestPerTile's result; `view`: the image's camera, its rotation (world to
    // view, a column-major 3 x 3 array, the camera at the origin), the projection's x and y
    // scales (three.js projectionMatrix elements 0 and 5) and near distance; `version`:
    // changes with every new image, so that lists sorted against an older one are sorted
    // again; `slack` (metres): how far the camera may be from where the image was taken while
    // lists sorted against it are drawn, by which every sphere is grown (turning alone changes
    // no ray from the camera, so it changes no occlusion).
    constructor({ tiles, columns, rows, width, height, tilePixels }, { rotation, scaleX, scaleY, near }, version, slack = 0) {
        Object.assign(this, { tiles, columns, rows, width, height, tilePixels, rotation, scaleX, scaleY, near, version, slack });
    }

    // Whether the sphere (centre relative to the image's camera, world axes; radius, metres,
    // before the slack) is hidden.
    hidesSphere(cx, cy, cz, sphereRadius) {
        const radius = sphereRadius + this.slack;
        const m = this.rotation;
        const vx = m[0] * cx + m[3] * cy + m[6] * cz;
        const vy = m[1] * cx + m[4] * cy + m[7] * cz;
        const depth = -(m[2] * cx + m[5] * cy + m[8] * cz);
        const nearest = depth - radius;
        if (!(nearest > this.near)) return false;
        const farthest = depth + radius;
        // The sphere's view-space box projects within these bounds: x / z over the box is
        // smallest at its least x and, for a negative x, its least depth.
        const lowX = (vx - radius) / (vx - radius < 0 ? nearest : farthest);
        const highX = (vx + radius) / (vx + radius > 0 ? nearest : farthest);
        const lowY = (vy - radius) / (vy - radius < 0 ? nearest : farthest);
        const highY = (vy + radius) / (vy + radius > 0 ? nearest : farthest);
        const x0 = this.tileOf(lowX * this.scaleX, this.width), x1 = this.tileOf(highX * this.scaleX, this.width);
        const y0 = this.tileOf(lowY * this.scaleY, this.height), y1 = this.tileOf(highY * this.scaleY, this.height);
        // Wholly off the screen: the frustum tests decide, not the tiles.
        if (x1 < 0 || y1 < 0 || x0 >= this.columns || y0 >= this.rows) return false;
        const cx0 = Math.max(x0, 0), cx1 = Math.min(x1, this.columns - 1);
        const cy0 = Math.max(y0, 0), cy1 = Math.min(y1, this.rows - 1);
        if ((cx1 - cx0 + 1) * (cy1 - cy0 + 1) > MAX_TILES) return false;
        for (let y = cy0; y <= cy1; ++y)
            for (let x = cx0; x <= cx1; ++x) if (this.tiles[y * this.columns + x] >= nearest) return false;
        return true;
    }

    // The tile column (or row) of normalised device coordinate `ndc` across an image `pixels`
    // wide (or high); outside the grid for points off the screen.
    tileOf(ndc, pixels) {
        return Math.floor(((ndc * 0.5 + 0.5) * pixels) / this.tilePixels);
    }
}
