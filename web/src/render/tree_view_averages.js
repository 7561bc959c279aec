// Per species and view, what a far tree's point shows (tree_points.js): the view's mean albedo
// and coverage and its mean normal, weighted by coverage over the view's inner square, as the
// native lod/tree_view_averages.cpp computes them from the EXR atlas. The viewer has the PNG
// atlases: albedo sRGB with coverage in alpha, normals n * 0.5 + 0.5 (impostor_views.js). The
// albedo is averaged in linear light, as the shaders blend it: an sRGB mean would darken
// every point.

// sRGB-encoded bytes to linear values, once.
const SRGB_TO_LINEAR = Float32Array.from({ length: 256 }, (_, i) => {
    const c = i / 255;
    return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
});

// `albedo`, `normal`: RGBA bytes of the two atlases, `width` texels a row (not premultiplied,
// as getImageData gives them); `layout`: the scene's tree_impostor_layout (grid,
// view_resolution, padding). Returns 8 floats per view, row-major as the tiles: mean linear
// albedo, coverage (the covered share of the inner square), mean normal (not unit), and the
// share of texels at least half covered: what a billboard cut out at one half covers, on a
// canvas without samples for alpha to coverage.
export function treeViewAverages(albedo, normal, width, layout) {
    const { grid, view_resolution: resolution, padding } = layout;
    const inner = resolution - 2 * padding;
    if (!(inner > 0) || width < grid * resolution || albedo.length < 4 * width * grid * resolution || normal.length !== albedo.length)
        throw new RangeError(`tree atlas of ${albedo.length / 4} texels does not hold ${grid} x ${grid} views of ${resolution}`);
    const out = new Float32Array(8 * grid * grid);
    for (let view = 0; view < grid * grid; ++view) {
        const x0 = (view % grid) * resolution + padding, y0 = Math.floor(view / grid) * resolution + padding;
        let r = 0, g = 0, b = 0, nx = 0, ny = 0, nz = 0, alpha = 0, solid = 0;
        for (let y = y0; y < y0 + inner; ++y) {
            for (let i = 4 * (y * width + x0), end = i + 4 * inner; i < end; i += 4) {
                const a = albedo[i + 3] / 255;
                if (a === 0) continue;
                r += a * SRGB_TO_LINEAR[albedo[i]];
                g += a * SRGB_TO_LINEAR[albedo[i + 1]];
                b += a * SRGB_TO_LINEAR[albedo[i + 2]];
                nx += a * (normal[i] / 127.5 - 1);
                ny += a * (normal[i + 1] / 127.5 - 1);
                nz += a * (normal[i + 2] / 127.5 - 1);
                alpha += a;
                solid += a >= 0.5;
            }
        }
        const texels = inner * inner;
        if (alpha > 0) out.set([r / alpha, g / alpha, b / alpha, alpha / texels, nx / alpha, ny / alpha, nz / alpha, solid / texels], 8 * view);
    }
    return out;
}

// An image's RGBA bytes, not premultiplied, in the browser: {data, width}. A 2D canvas keeps
// colour premultiplied by alpha, which costs a colour precision where alpha is low; the
// normal atlas's alpha is the depth toward the camera (0.5 at the sphere's centre), high on
// the surfaces a view sees, and the albedo's low-alpha texels weigh little in the means.
export function imagePixels(image) {
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext('2d', { willReadFrequently: true });
    context.drawImage(image, 0, 0);
    return { data: context.getImageData(0, 0, image.width, image.height).data, width: image.width };
}
