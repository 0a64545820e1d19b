// SPDX-License-Identifier: MIT
// stroke.frag: coverage-based anti-aliasing from the exact distance of the
// pixel centre to the primitive; round joins whose two round caps are split
// at the bisector of the turn (each pixel belongs to exactly one segment, so
// no seam and no double blending, and no miter spike past a sharp turning
// point); dash patterns along the path's arc length.
#version 330 core
flat in vec4 v_p;
flat in vec4 v_c0;
flat in vec4 v_c1;
flat in vec4 v_w;
flat in vec4 v_m;
uniform vec2 u_size;
uniform int u_ndash;          // 0: solid; else an even number of on/off lengths
uniform float u_dash[8];
uniform float u_dash_total;
out vec4 o_colour;

#ifdef HY_DASHES
// Signed distance along the path from arc length s to the nearest "on"
// interval of the dash pattern: negative inside one.
float dash_gap(float s)
{
    float p = mod(s, u_dash_total), best = 1e9, acc = 0.0;
    for (int i = 0; i < 8; i += 2) {
        if (i < u_ndash) {
            float on = u_dash[i], off = u_dash[i + 1];
            float a = acc, b = acc + on;
            best = min(best, max(a - p, p - b));
            best = min(best, max(a - p + u_dash_total, p - u_dash_total - b));
            best = min(best, max(a - p - u_dash_total, p + u_dash_total - b));
            acc += on + off;
        }
    }
    return best;
}
#endif

// Coverage of a segment (flags: 1 butt start, 2 butt end, 4 round dashes,
// 8 joint at the start, 16 joint at the end: cut by the split plane in v_m);
// t receives the position along it in [0, 1].
float segment(vec2 pos, float hw, int flags, out float t)
{
    vec2 a = v_p.xy, b = v_p.zw, ab = b - a;
    float len = length(ab);
    vec2 d = len > 0.0 ? ab / len : vec2(1.0, 0.0);
    float s = dot(pos - a, d), perp = abs(dot(pos - a, vec2(-d.y, d.x)));
    if ((flags & 8) != 0 && dot(pos - a, v_m.xy) < 0.0)
        return 0.0;
    if ((flags & 16) != 0 && dot(pos - b, v_m.zw) >= 0.0)
        return 0.0;
    float dist = length(pos - (a + d * clamp(s, 0.0, len)));
    float cov = clamp(hw + 0.5 - dist, 0.0, 1.0);
    if ((flags & 1) != 0)
        cov = min(cov, clamp(s + 0.5, 0.0, 1.0) * clamp(hw + 0.5 - perp, 0.0, 1.0));
    if ((flags & 2) != 0)
        cov = min(cov, clamp(len - s + 0.5, 0.0, 1.0) * clamp(hw + 0.5 - perp, 0.0, 1.0));
#ifdef HY_DASHES
    // compiled into the dashed variant only, so solid strokes carry no dash
    // code; dash_gap's loop has a constant bound so that llvmpipe unrolls it
    if (u_ndash > 0) {
        float g = dash_gap(v_w.y + s);
        if ((flags & 4) != 0)
            cov = min(cov, clamp(hw + 0.5 - length(vec2(max(g, 0.0), perp)), 0.0, 1.0));
        else
            cov = min(cov, clamp(0.5 - g, 0.0, 1.0));
    }
#endif
    t = len > 0.0 ? clamp(s / len, 0.0, 1.0) : 0.0;
    return cov;
}

void main()
{
    // the pixel centre, y down: exact and identical for every primitive
    vec2 pos = vec2(gl_FragCoord.x, u_size.y - gl_FragCoord.y);
    int kind = int(v_w.z + 0.5);
    float hw = v_w.x, cov, t = 0.0;
    if (kind == 0) {
        cov = segment(pos, hw, int(v_w.w + 0.5), t);
    } else if (kind == 1) {
        vec2 lo = pos - v_p.xy, hi = v_p.zw - pos;
        cov = clamp(0.5 + min(lo.x, hi.x), 0.0, 1.0) * clamp(0.5 + min(lo.y, hi.y), 0.0, 1.0);
    } else if (kind == 2) {
        cov = clamp(hw + 0.5 - length(pos - v_p.xy), 0.0, 1.0);
    } else {
        cov = clamp(hw + 0.5 - abs(length(pos - v_p.xy) - v_p.z), 0.0, 1.0);
    }
    vec4 c = mix(v_c0, v_c1, t);
    if (cov * c.a <= 0.0)
        discard;
    o_colour = vec4(c.rgb, c.a * cov);
}
