#version 450 core
#extension GL_ARB_gpu_shader_int64 : require
// LOD1: a base volume's walls ray-cast per pixel through their grammar (Marvie et al. 2011):
// the wall pixel's element resumes the grammar at its stop rule, lod1Walk finds the terminal
// under the pixel, and the terminal's central impostor view is sampled where the pixel lies
// in it. The depth is the wall's own. Near its far end LOD1 blends into LOD0's wall texture.
#include "frame.glsl"

uniform sampler2DArray impostorAlbedo, impostorNormalDepth;
uniform usampler2D impostorTableViews;
uniform sampler2D impostorTableWeights;
uniform uvec4 impostorLayout;
#include "impostor_views.glsl"
#include "lod1.glsl"
#include "wall_texture.glsl"

struct Lod1Element {
    vec4 origin, axisX, axisY;
    uvec4 rule;
    ivec4 state;
    uvec4 state2, state3;
};
layout(std430, binding = 8) readonly buffer ShapeBuffer { GpuShape shapes[]; };
layout(std430, binding = 9) readonly buffer SphereBuffer { vec4 spheres[]; };
layout(std430, binding = 12) readonly buffer ElementBuffer { Lod1Element lod1Elements[]; };

uniform uint shapeBase;   // the global index of this grammar's shape 0
uniform uint centralView; // the impostor view nearest the wall's normal
uniform float lod0Blend;  // 1: LOD0 only

in vec3 vNormal;
in vec3 vAlbedo;
in vec3 vPosition;
in vec3 vLocal;
flat in float vElement;
layout(location = 0) out vec4 colour;
layout(location = 1) out vec4 terminalId; // x: outcome + 1 (0: no element); y: shape (tests)

void main() {
    vec3 n = normalize(gl_FrontFacing ? vNormal : -vNormal);
    vec3 wall = vAlbedo, lod1 = vAlbedo, lod1Normal = n;
    terminalId = vec4(0.0);
    if (vElement >= 0.0 && lod0Blend < 1.0) {
        Lod1Element e = lod1Elements[uint(vElement)];
        Lod1Context c;
        c.origin = e.origin.xyz;
        c.axisX = e.axisX.xyz;
        c.axisY = e.axisY.xyz;
        c.normal = normalize(cross(c.axisX, c.axisY));
        c.baseZ = e.origin.w;
        c.atom = e.state2.z;
        c.atoms = e.state2.w;
        c.building = e.state3.x;
        c.parameters = e.rule.y;
        lod1LoadParameters(c.parameters);
        c.buildingKey = packUint2x32(e.rule.zw);
        Lod1Scope s;
        s.origin = vec2(0.0);
        s.size = vec2(e.axisX.w, e.axisY.w);
        s.key = packUint2x32(e.state3.yz);
        s.floor = e.state.x;
        s.floors = e.state.y;
        s.index = e.state.z;
        s.count = e.state.w;
        s.level = e.state2.x;
        s.depth = e.state2.y;
        vec3 local = vLocal - c.origin;
        vec2 point = vec2(dot(local, c.axisX), dot(local, c.axisY));
        Lod1Hit hit = lod1Walk(e.rule.x, s, c, point);
        terminalId = vec4(float(hit.outcome + 1u), float(hit.shape), 0.0, 1.0);
        if (hit.outcome == LOD1_TERMINAL) {
            GpuShape shape = shapes[shapeBase + hit.shape];
            if (shape.nominalSize.w >= 0.0) {
                uint layer = uint(shape.nominalSize.w);
                vec4 sphere = spheres[layer];
                vec2 unit = (point - hit.origin) / max(hit.size, vec2(1e-6));
                vec3 nominal = vec3(unit * shape.nominalSize.xy, 0.0);
                vec3 viewForward = impostorViewDirection(centralView), right, up;
                impostorBasis(viewForward, impostorLayout.w, right, up);
                vec3 q = (nominal - sphere.xyz) / sphere.w;
                vec2 uv = vec2(dot(q, right), dot(q, up));
                vec4 a = impostorSample(impostorAlbedo, layer, centralView, uv);
                if (a.a > 0.5) {
                    lod1 = a.rgb;
                    vec3 stored = impostorSample(impostorNormalDepth, layer, centralView, uv).xyz;
                    float depthRatio = shape.nominalSize.z / max(min(shape.nominalSize.x, shape.nominalSize.y), 1e-6);
                    vec3 scope = vec3(hit.size, depthRatio * min(hit.size.x, hit.size.y));
                    lod1Normal = mat3(c.axisX, c.axisY, c.normal) *
                                 scopeNormal(normalize(stored), shape.nominalSize.xyz, scope);
                }
            }
        }
    }
    vec3 lod0 = wallTexture(wall, n, vLocal);
    vec3 lit1 = shade(lod1, normalize(lod1Normal), vPosition), lit0 = shade(lod0, n, vPosition);
    colour = vec4(mix(lit1, lit0, lod0Blend), 1.0);
}
