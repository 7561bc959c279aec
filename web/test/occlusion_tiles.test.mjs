// Occlusion tiles (src/stream/occlusion_tiles.js): the farthest depth per tile, its border,
// and which spheres the tiles hide. The camera looks along -z with world and view axes alike,
// at a 40 x 20 pixel depth image of 4-pixel tiles; the browser test (occlusion.e2e.mjs) checks
// the images with and without culling against each other.
import assert from 'node:assert/strict';
import test from 'node:test';

import { farthestPerTile, MAX_TILES, OcclusionTiles } from '../src/stream/occlusion_tiles.js';

const width = 40, height = 20, tilePixels = 4;
const identity = [1, 0, 0, 0, 1, 0, 0, 0, 1];
// x and y scales of a 90 degree vertical field of view at a 2:1 aspect.
const view = { rotation: identity, scaleX: 0.5, scaleY: 1, near: 0.5 };

// A wall 10 m away over the left half of the image (x < 0), nothing on the right.
function leftWall() {
    const depths = new Float32Array(width * height).fill(Infinity);
    for (let y = 0; y < height; ++y) for (let x = 0; x < width / 2; ++x) depths[y * width + x] = 10;
    return depths;
}

test('a tile holds the farthest depth of its pixels and a one-pixel border', () => {
    const depths = new Float32Array(width * height).fill(5);
    depths[3 * width + 4] = 9; // in tile (1, 0), on the border of tile (0, 0)
    depths[10 * width + 20] = Infinity;
    const { tiles, columns, rows } = farthestPerTile(depths, width, height, tilePixels);
    assert.equal(columns, 10);
    assert.equal(rows, 5);
    assert.equal(tiles[0], 9, 'the border counts');
    assert.equal(tiles[1], 9);
    assert.equal(tiles[2], 5, 'two pixels away does not');
    assert.equal(tiles[2 * columns + 5], Infinity);
    assert.equal(tiles[2 * columns + 4], Infinity, 'nothing drawn on the border is nothing drawn');
    // A partial last tile.
    assert.equal(farthestPerTile(new Float32Array(9 * 5).fill(1), 9, 5, 4).columns, 3);
});

test('a sphere behind the wall is hidden; beside it, in front of it or across its edge it is not', () => {
    const tiles = new OcclusionTiles(farthestPerTile(leftWall(), width, height, tilePixels), view, 1);
    assert.equal(tiles.hidesSphere(-20, 0, -30, 1), true, 'behind the wall');
    assert.equal(tiles.hidesSphere(20, 0, -30, 1), false, 'beside it, where nothing is drawn');
    assert.equal(tiles.hidesSphere(-2, 0, -5, 1), false, 'in front of it');
    assert.equal(tiles.hidesSphere(-20, 0, -10.5, 1), false, 'reaching in front of it');
    assert.equal(tiles.hidesSphere(-1, 0, -30, 2), false, 'across its edge');
    assert.equal(tiles.hidesSphere(0, 0, 0.2, 1), false, 'around the camera');
    assert.equal(tiles.hidesSphere(-20, 0, 30, 1), false, 'behind the camera');
    assert.equal(tiles.hidesSphere(-200, 0, -30, 1), false, 'off the screen');
});

test('a sphere is grown by the slack the camera may move', () => {
    const image = farthestPerTile(leftWall(), width, height, tilePixels);
    assert.equal(new OcclusionTiles(image, view, 1, 0).hidesSphere(-20, 0, -12, 1), true);
    assert.equal(new OcclusionTiles(image, view, 1, 1.5).hidesSphere(-20, 0, -12, 1), false);
});

test('a sphere over more than MAX_TILES tiles is not tested', () => {
    const big = 40, image = new Float32Array(big * big).fill(1);
    const tiles = new OcclusionTiles(farthestPerTile(image, big, big, 1), { ...view, scaleX: 1 }, 1);
    // 40 x 40 tiles of one pixel: a sphere over a fifth of the screen each way covers 64.
    assert.equal(tiles.hidesSphere(0, 0, -100, 9), true, `${MAX_TILES} tiles or fewer`);
    assert.equal(tiles.hidesSphere(0, 0, -100, 30), false);
});

test('the view rotation is applied: a wall to the east hides what lies behind it looking east', () => {
    // Looking along +x: view x = world -y... as three.js's lookAt gives (right = forward x up).
    const rotation = [0, 0, -1, -1, 0, 0, 0, 1, 0]; // world to view, column-major
    const tiles = new OcclusionTiles(farthestPerTile(new Float32Array(width * height).fill(10), width, height, tilePixels), { ...view, rotation }, 1);
    assert.equal(tiles.hidesSphere(30, 0, 0, 1), true, 'ahead, behind the wall');
    assert.equal(tiles.hidesSphere(5, 0, 0, 1), false, 'ahead, in front of it');
    assert.equal(tiles.hidesSphere(-30, 0, 0, 1), false, 'behind the camera');
});
