// The LOD policy of the native renderer, for the browser (ARCHITECTURE.md §5; the rules of
// cells/include/hexlod/cells/scheduler.h and lod/include/hexlod/lod/cull_shared.h, with the
// numbers of the scene's LOD profile from /api/v1/scene):
// - per cell, the 3D Tiles screen-space error of its extruded set,
//   sse = geometric_error[1] * viewport_height / (distance * 2 tan(fov_y / 2)), distance from the
//   camera to the nearest point of the cell's bounds box (inside it: infinite); terminal sets
//   above max_sse * (1 + hysteresis), the extruded set below max_sse * (1 - hysteresis), the
//   previous choice in between (every cell starts extruded);
// - per terminal, by the distance to its scope centre: LOD4, LOD3 from the distance at which
//   geometric_error[3] stays under max_sse, LOD2 from geometric_error[2]'s; a facade's terminal
//   whose camera is behind the plane its shape recedes to is culled (backface; a tree's parts
//   stand free and are seen from every side), and without impostors every visible terminal is
//   LOD4;
// - per LOD4 terminal of a shape with a coarse mesh, that mesh once the two
//   meshes' deviation, scaled by the terminal's scope, projects under max_sse from its scope
//   centre (meshShape in cull_shared.h).
export const EXTRUDED = 'extruded';
export const TERMINALS = 'terminals';

// The pixels one metre spans at one metre's distance.
export function screenScale(viewportHeight, fovY) {
    return viewportHeight / (2 * Math.tan(0.5 * fovY));
}

export function screenSpaceError(geometricError, distance, viewportHeight, fovY) {
    if (distance <= 0) return Infinity;
    return (geometricError * screenScale(viewportHeight, fovY)) / distance;
}

// The distance from which a LOD of this geometric error stays under the profile's budget.
export function lodDistance(geometricError, profile, fovY, viewportHeight) {
    return (geometricError * screenScale(viewportHeight, fovY)) / profile.max_screen_space_error;
}

// Distance from point p to the box [min, max] (arrays of 3), 0 inside.
export function distanceToBox(p, min, max) {
    let sum = 0;
    for (let i = 0; i < 3; ++i) {
        const d = p[i] < min[i] ? min[i] - p[i] : p[i] > max[i] ? p[i] - max[i] : 0;
        sum += d * d;
    }
    return Math.sqrt(sum);
}

export function nextCellLod(previous, sse, profile) {
    const maxSse = profile.max_screen_space_error, band = profile.hysteresis;
    if (sse > maxSse * (1 + band)) return TERMINALS;
    if (sse < maxSse * (1 - band)) return EXTRUDED;
    return previous;
}

// A cell's decision for this camera: {distance, sse, lod}.
export function decideCell(previous, bounds, camera, profile) {
    const distance = distanceToBox(camera.position, bounds.min, bounds.max);
    const sse = screenSpaceError(profile.geometric_error[1], distance, camera.viewportHeight, camera.fovY);
    return { distance, sse, lod: nextCellLod(previous ?? EXTRUDED, sse, profile) };
}

// The per-terminal distances for this camera: {lod3, lod2} in metres.
// `coarse`: the distance per metre of mesh deviation from which a coarse mesh stays under the
// budget (coarseMeshReach).
export function terminalLodDistances(profile, camera) {
    return {
        lod3: lodDistance(profile.geometric_error[3], profile, camera.fovY, camera.viewportHeight),
        lod2: lodDistance(profile.geometric_error[2], profile, camera.fovY, camera.viewportHeight),
        coarse: lodDistance(1, profile, camera.fovY, camera.viewportHeight),
    };
}

// The distance from a terminal's scope centre beyond which its shape's coarse mesh stays under
// the budget: the meshes' `deviation` (per unit-scope axis, from the scene's coarse_mesh)
// scaled by the scope (w, h, d), times `perMetre` (terminalLodDistances' `coarse`).
export function coarseMeshReach(deviation, w, h, d, perMetre) {
    return Math.hypot(deviation[0] * w, deviation[1] * h, deviation[2] * d) * perMetre;
}

// Whether a camera at `camera` has moved far enough from `last` (the position a distance
// decision was last made at; null: never) for a decision made at `distance` metres to change:
// by 2 % of it, and at least half a metre, so a hovering camera re-decides nothing.
export function movedEnough(last, camera, distance) {
    if (!last) return true;
    return Math.hypot(camera[0] - last[0], camera[1] - last[1], camera[2] - last[2]) >= moveTolerance(distance);
}

// How far the camera may move before movedEnough re-makes a decision made at `distance`.
export function moveTolerance(distance) {
    return Math.max(0.5, 0.02 * distance);
}

// The view a batch's terminal lists are sorted for, or null for no frustum test: `sides`, the
// frustum's four side planes ({normal: [x, y, z], constant}, normals inward; three.js's
// Frustum.planes[0..3]) with the camera at the origin, and `forward`, the unit view direction.
// The lists are sorted with every side plane turned outwards by TURN_MARGIN radians, and sorted
// again once the view has turned by half that (turnedEnough): a view turned by less than the
// margin shows nothing the lists left out.
export const TURN_MARGIN = (10 * Math.PI) / 180;

export function turnedEnough(last, forward) {
    if (!last) return true;
    const cos = last[0] * forward[0] + last[1] * forward[1] + last[2] * forward[2];
    return cos < Math.cos(0.5 * TURN_MARGIN);
}

// Whether the sphere (centre relative to the camera, radius) lies wholly outside one of the
// view's side planes turned outwards by TURN_MARGIN. Turning a plane through the camera by an
// angle a moves a point's signed distance to it by at most |point| sin a.
export function outsideView(view, cx, cy, cz, radius) {
    const reach = radius + Math.hypot(cx, cy, cz) * Math.sin(TURN_MARGIN);
    for (const { normal, constant } of view.sides)
        if (normal[0] * cx + normal[1] * cy + normal[2] * cz + constant < -reach) return true;
    return false;
}

// 0 (culled), 2, 3 or 4 for a terminal whose scope corner is at `corner` relative to the camera,
// with scope axes X, Y, Z (from quaternionAxes: nine numbers), size (w, h) and depth d, or
// COARSE (a LOD4 terminal drawn with its shape's coarse mesh) when `coarseReach` (metres,
// coarseMeshReach; Infinity: the shape has none) is no farther than its scope centre. With a
// `view`, a terminal outside it is culled too; `slack` (metres) is how far the camera may move
// before the decision is made again: it widens the view test and narrows the coarse mesh's
// range, so neither decision is wrong until then. With `occlusion` (an OcclusionTiles), a
// terminal behind the opaque base volumes is OCCLUDED. `onWall`: false for a tree's parts,
// which no wall hides from behind.
export const COARSE = 'coarse';
// classifyTerminal's answer for a terminal that the `occlusion` tiles (occlusion_tiles.js) hide.
export const OCCLUDED = 'occluded';

export function classifyTerminal(corner, axes, w, h, d, distances, impostors, view = null, slack = 0, coarseReach = Infinity, occlusion = null, onWall = true) {
    const cx = corner[0] + axes[0] * 0.5 * w + axes[3] * 0.5 * h;
    const cy = corner[1] + axes[1] * 0.5 * w + axes[4] * 0.5 * h;
    const cz = corner[2] + axes[2] * 0.5 * w + axes[5] * 0.5 * h;
    const inFront = -(axes[6] * corner[0] + axes[7] * corner[1] + axes[8] * corner[2]);
    if (onWall && inFront < -d) return 0;
    // The scope box's half diagonal, doubled: a mesh may reach past its scope (a balcony's
    // depth ratio is above 1), and an impostor quad covers the mesh's bounds.
    const radius = Math.hypot(w, h, d);
    if (view && outsideView(view, cx, cy, cz, radius + slack)) return 0;
    if (occlusion && occlusion.hidesSphere(cx, cy, cz, radius)) return OCCLUDED;
    const distance = Math.sqrt(cx * cx + cy * cy + cz * cz);
    const lod = !impostors ? 4 : distance >= distances.lod2 ? 2 : distance >= distances.lod3 ? 3 : 4;
    return lod === 4 && distance - slack >= coarseReach ? COARSE : lod;
}
