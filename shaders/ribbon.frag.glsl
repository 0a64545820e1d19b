// SPDX-License-Identifier: MIT
// ribbon.frag: two-sided Blinn-Phong lighting with one directional light
// (eye space) plus ambient.
#version 330 core
in vec3 v_normal;
in vec3 v_eye;
in vec3 v_colour;
uniform vec3 u_light;         // direction towards the light, eye space
out vec4 o_colour;

void main()
{
    vec3 n = normalize(v_normal), v = normalize(-v_eye);
    if (dot(n, v) < 0.0)          // two-sided: light the side the camera sees
        n = -n;
    vec3 l = normalize(u_light), h = normalize(l + v);
    float diff = max(dot(n, l), 0.0);
    float spec = pow(max(dot(n, h), 0.0), 40.0) * 0.35;
    vec3 c = v_colour * (0.35 + 0.75 * diff) + vec3(spec);
    o_colour = vec4(min(c, vec3(1.0)), 1.0);
}
