// SPDX-License-Identifier: MIT
// plane.frag: the relay plane of a Preisach model (hy_gl.h, hy_gl_plane).
// Each pixel is the relay (alpha, beta) at its centre: beta across, alpha up,
// only alpha >= beta.  Its state replays the staircase memory s[0..n]
// (alternating extrema; s[0] a minimum when u_kind0 < 0): the last extremum
// that reached it decides, a maximum >= alpha switches it up, a minimum <=
// beta down.  Its colour is the up or down colour, deeper where the factorised
// density f((alpha - ma)/sa) f((beta - mb)/sb) (peak 1) is larger.
#version 330 core
uniform vec4 u_rect;          // the panel: x, y (top, y down), w, h in pixels
uniform float u_height;       // the frame's height in pixels
uniform vec4 u_range;         // beta lo, beta hi, alpha lo, alpha hi
uniform float u_s[64];
uniform int u_n;
uniform int u_kind0;          // +1: s[0] is a maximum, -1 a minimum
uniform int u_dist;           // 0 Gaussian, 1 Lorentzian
uniform vec4 u_dens;          // ma, sa, mb, sb
uniform vec3 u_up;
uniform vec3 u_down;
out vec4 o_colour;

float shape(float z)
{
    return u_dist == 0 ? exp(-0.5 * z * z) : 1.0 / (1.0 + z * z);
}

void main()
{
    float px = gl_FragCoord.x, py = u_height - gl_FragCoord.y;
    float beta = u_range.x + (px - u_rect.x) / u_rect.z * (u_range.y - u_range.x);
    float alpha = u_range.w - (py - u_rect.y) / u_rect.w * (u_range.w - u_range.z);
    if (alpha < beta)
        discard;
    int state = u_kind0 > 0 ? 1 : -1;
    int kind = u_kind0;
    for (int j = 1; j <= u_n; j++) {
        kind = -kind;
        if (kind > 0 && u_s[j] >= alpha)
            state = 1;
        else if (kind < 0 && u_s[j] <= beta)
            state = -1;
    }
    float w = shape((alpha - u_dens.x) / u_dens.y) * shape((beta - u_dens.z) / u_dens.w);
    vec3 base = state > 0 ? u_up : u_down;
    w = floor(w * 32.0 + 0.5) / 32.0;    // 33 shades: flat bands compress (PNG) far better than a gradient
    o_colour = vec4(mix(vec3(1.0), base, 0.12 + 0.88 * w), 1.0);
}
