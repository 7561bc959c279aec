// Impostor views on the GPU: the view frame, tile sampling and the four-view reconstruction
// with parallax correction. The same steps as impostor_reconstruction.cpp and view_layout.cpp
// (viewBasis); tests hold the two together.
//
// Needs, before inclusion:
//   uniform sampler2DArray impostorAlbedo, impostorNormalDepth; // one layer per shape
//   uniform usampler2D impostorTableViews;  // the layout's DirectionTable: 4 view indices
//   uniform sampler2D impostorTableWeights; // and their weights
//   uniform uvec4 impostorLayout;           // grid, view resolution, padding, sphere (0 hemi, 1 full)

vec3 impostorUp(vec3 forward, uint sphere) {
    vec3 primary = sphere == 0u ? vec3(0, 1, 0) : vec3(0, 0, 1);
    vec3 secondary = sphere == 0u ? vec3(0, 0, 1) : vec3(0, 1, 0);
    return abs(dot(forward, primary)) > 0.999 ? secondary : primary;
}

// Right and up of the view looking back along `forward` (toward the viewer).
void impostorBasis(vec3 forward, uint sphere, out vec3 right, out vec3 up) {
    right = normalize(cross(impostorUp(forward, sphere), forward));
    up = cross(forward, right);
}

vec3 impostorViewDirection(uint view) {
    uint grid = impostorLayout.x;
    vec2 cell = vec2(float(view % grid), float(view / grid));
    if (impostorLayout.w == 0u) {
        vec2 p = cell * (2.0 / float(grid - 1u)) - 1.0;
        float x = 0.5 * (p.x + p.y), y = 0.5 * (p.x - p.y);
        return normalize(vec3(x, y, max(0.0, 1.0 - abs(x) - abs(y))));
    }
    vec2 p = (cell + 0.5) * (2.0 / float(grid)) - 1.0;
    vec3 d = vec3(p, 1.0 - abs(p.x) - abs(p.y));
    if (d.z < 0.0) d.xy = (1.0 - abs(p.yx)) * vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
    return normalize(d);
}

// The (hemi-)octahedral square position of a direction, in [0, 1]^2, for the table.
vec2 impostorTablePosition(vec3 d) {
    if (impostorLayout.w == 0u) {
        d.z = max(d.z, 0.0);
        if (d.x == 0.0 && d.y == 0.0 && d.z == 0.0) d.z = 1.0;
        vec2 p = d.xy / (abs(d.x) + abs(d.y) + abs(d.z));
        return vec2(p.x + p.y, p.x - p.y) * 0.5 + 0.5;
    }
    vec2 p = d.xy / (abs(d.x) + abs(d.y) + abs(d.z));
    if (d.z < 0.0) p = (1.0 - abs(p.yx)) * vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
    return p * 0.5 + 0.5;
}

// Bilinear sample of a view's tile at view coordinates uv in [-1, 1], clamped to the inner area.
vec4 impostorSample(sampler2DArray atlas, uint layer, uint view, vec2 uv) {
    float resolution = float(impostorLayout.y), padding = float(impostorLayout.z);
    float inner = resolution - 2.0 * padding;
    uint grid = impostorLayout.x;
    vec2 texel = padding + vec2(uv.x * 0.5 + 0.5, 0.5 - uv.y * 0.5) * inner - 0.5;
    texel = clamp(texel, vec2(padding), vec2(padding + inner - 1.0));
    vec2 tile = vec2(float(view % grid), float(view / grid)) * resolution;
    return texture(atlas, vec3((tile + texel + 0.5) / (float(grid) * resolution), float(layer)));
}

// The four views and weights for a direction, from the table (nearest texel).
void impostorViews(vec3 forward, out uvec4 views, out vec4 weights) {
    ivec2 size = textureSize(impostorTableWeights, 0);
    ivec2 texel = clamp(ivec2(impostorTablePosition(forward) * vec2(size)), ivec2(0), size - 1);
    views = texelFetch(impostorTableViews, texel, 0);
    weights = texelFetch(impostorTableWeights, texel, 0);
}

// Reconstructs the shape along a ray in its normalised frame (positions relative to the
// bounding sphere's centre, in radii): `rayOrigin` on the plane through the centre across
// `forward`, the ray running along `forward` toward the viewer. Returns albedo with coverage;
// `normalDepth` gets the blended shape-space normal and the depth along `forward`. Only the
// first `viewCount` views are read, and of those the ones with a weight: a caller that uses
// the nearest view alone passes 1. llvmpipe runs every iteration that any pixel of a SIMD
// group runs, masked, and skips a view's reads only when the loop ends before it: the weights
// come largest first (view_lookup.h), so the loop ends at the first zero, and a group whose
// pixels all blend two views reads two.
vec4 impostorReconstruct(uint layer, vec3 rayOrigin, vec3 forward, uvec4 views, vec4 weights, uint viewCount,
                         uint iterations, out vec4 normalDepth) {
    vec4 colour = vec4(0.0);
    vec4 nd = vec4(0.0);
    float coverage = 0.0;
    for (uint i = 0u; i < min(viewCount, 4u); ++i) {
        if (weights[i] <= 0.0) break;
        vec3 viewForward = impostorViewDirection(views[i]), right, up;
        impostorBasis(viewForward, impostorLayout.w, right, up);
        float s = 0.0;
        vec2 uv = vec2(0.0);
        for (uint iteration = 0u;; ++iteration) {
            vec3 q = rayOrigin + s * forward;
            uv = vec2(dot(q, right), dot(q, up));
            if (iteration == iterations) break;
            float depth = impostorSample(impostorNormalDepth, layer, views[i], uv).w;
            vec3 surface = uv.x * right + uv.y * up + depth * viewForward;
            s = dot(surface - rayOrigin, forward);
        }
        vec4 a = impostorSample(impostorAlbedo, layer, views[i], uv);
        vec4 n = impostorSample(impostorNormalDepth, layer, views[i], uv);
        float w = weights[i] * a.a;
        colour += w * vec4(a.rgb, 1.0);
        vec3 surface = uv.x * right + uv.y * up + n.w * viewForward;
        nd += w * vec4(n.xyz, dot(surface, forward));
        coverage += w;
    }
    if (coverage <= 0.0) {
        normalDepth = vec4(0.0, 0.0, 0.0, -1.0);
        return vec4(0.0);
    }
    normalDepth = vec4(length(nd.xyz) > 0.0 ? normalize(nd.xyz) : vec3(0.0), nd.w / colour.w);
    return vec4(colour.rgb / colour.w, min(coverage, 1.0));
}
