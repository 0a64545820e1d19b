// stroke.frag: coverage-based anti-aliasing from the exact distance of the
// pixel centre to the primitive; dash patterns along the path's arc length.
#version 330 core
in vec2 v_pos;
flat in vec4 v_p;
flat in vec4 v_c0;
flat in vec4 v_c1;
flat in vec4 v_w;
uniform int u_ndash;          // 0: solid; else an even number of on/off lengths
uniform float u_dash[8];
uniform float u_dash_total;
out vec4 o_colour;

// Signed distance along the path from arc length s to the nearest "on"
// interval of the dash pattern: negative inside one.
float dash_gap(float s)
{
    float p = mod(s, u_dash_total), best = 1e9, acc = 0.0;
    for (int i = 0; i < u_ndash; i += 2) {
        float a = acc, b = acc + u_dash[i];
        for (int k = -1; k <= 1; k++) {
            float q = p + float(k) * u_dash_total;
            best = min(best, max(a - q, q - b));
        }
        acc += u_dash[i] + u_dash[i + 1];
    }
    return best;
}

void main()
{
    int kind = int(v_w.z + 0.5);
    float hw = v_w.x, cov, t = 0.0;
    if (kind == 0) {
        vec2 a = v_p.xy, ab = v_p.zw - v_p.xy;
        float len = length(ab);
        vec2 d = len > 0.0 ? ab / len : vec2(1.0, 0.0);
        float s = dot(v_pos - a, d), sc = clamp(s, 0.0, len);
        float perp = abs(dot(v_pos - a, vec2(-d.y, d.x)));
        float dist = length(v_pos - (a + d * sc));
        int flags = int(v_w.w + 0.5);
        cov = clamp(hw + 0.5 - dist, 0.0, 1.0);
        if ((flags & 1) != 0)
            cov = min(cov, clamp(s + 0.5, 0.0, 1.0) * clamp(hw + 0.5 - perp, 0.0, 1.0));
        if ((flags & 2) != 0)
            cov = min(cov, clamp(len - s + 0.5, 0.0, 1.0) * clamp(hw + 0.5 - perp, 0.0, 1.0));
        if (u_ndash > 0) {
            float g = dash_gap(v_w.y + s);
            if ((flags & 4) != 0)
                cov = min(cov, clamp(hw + 0.5 - length(vec2(max(g, 0.0), perp)), 0.0, 1.0));
            else
                cov = min(cov, clamp(0.5 - g, 0.0, 1.0));
        }
        t = len > 0.0 ? sc / len : 0.0;
    } else if (kind == 1) {
        vec2 lo = v_pos - v_p.xy, hi = v_p.zw - v_pos;
        cov = clamp(0.5 + min(lo.x, hi.x), 0.0, 1.0) * clamp(0.5 + min(lo.y, hi.y), 0.0, 1.0);
    } else if (kind == 2) {
        cov = clamp(hw + 0.5 - length(v_pos - v_p.xy), 0.0, 1.0);
    } else {
        cov = clamp(hw + 0.5 - abs(length(v_pos - v_p.xy) - v_p.z), 0.0, 1.0);
    }
    vec4 c = mix(v_c0, v_c1, t);
    if (cov * c.a <= 0.0)
        discard;
    o_colour = vec4(c.rgb, c.a * cov);
}
