// SPDX-License-Identifier: MIT
// plane.vert: one quad over the viewport (the panel), from gl_VertexID.
#version 330 core
void main()
{
    vec2 p = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    gl_Position = vec4(p, 0.0, 1.0);
}
