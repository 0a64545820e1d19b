// SPDX-License-Identifier: MIT
// stroke.vert: one instance per primitive (segment, box, disc, ring);
// expands it to a screen-aligned quad with a one-pixel margin for coverage AA.
// Segment ends are round caps (possibly cut by a joint's split plane), so a
// segment reaches half a width past its ends.
#version 330 core
layout(location = 0) in vec4 a_p;   // segment: p0.xy p1.xy; box: min.xy max.xy; disc/ring: centre.xy (radius, -)
layout(location = 1) in vec4 a_c0;  // colour at p0 (straight alpha)
layout(location = 2) in vec4 a_c1;  // colour at p1
layout(location = 3) in vec4 a_w;   // half width, arc length at p0, kind, flags
layout(location = 4) in vec4 a_m;   // joint split-plane normals at p0 and p1 (pointing forward)
uniform vec2 u_size;                // framebuffer size in pixels
flat out vec4 v_p;
flat out vec4 v_c0;
flat out vec4 v_c1;
flat out vec4 v_w;
flat out vec4 v_m;

void main()
{
    int kind = int(a_w.z + 0.5);
    float m = a_w.x + 1.0;
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 pos;
    if (kind == 0) {
        vec2 ab = a_p.zw - a_p.xy;
        float len = length(ab);
        vec2 d = len > 0.0 ? ab / len : vec2(1.0, 0.0);
        vec2 n = vec2(-d.y, d.x);
        vec2 base = corner.x < 0.5 ? a_p.xy - d * m : a_p.zw + d * m;
        pos = base + n * (corner.y < 0.5 ? -m : m);
    } else if (kind == 1) {
        vec2 lo = a_p.xy - vec2(1.0), hi = a_p.zw + vec2(1.0);
        pos = mix(lo, hi, corner);
    } else {
        float r = (kind == 2 ? a_w.x : a_p.z + a_w.x) + 1.0;
        pos = a_p.xy + (corner * 2.0 - 1.0) * r;
    }
    v_p = a_p;
    v_c0 = a_c0;
    v_c1 = a_c1;
    v_w = a_w;
    v_m = a_m;
    gl_Position = vec4(pos.x / u_size.x * 2.0 - 1.0, 1.0 - pos.y / u_size.y * 2.0, 0.0, 1.0);
}
