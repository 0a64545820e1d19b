// SPDX-License-Identifier: MIT
// ribbon.vert: the 3-D convergence ribbon; positions in a unit box, one
// model-view-projection matrix, normals rotated by the model-view part.
#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_colour;
uniform mat4 u_mvp;
uniform mat4 u_mv;
out vec3 v_normal;
out vec3 v_eye;
out vec3 v_colour;

void main()
{
    gl_Position = u_mvp * vec4(a_pos, 1.0);
    v_eye = (u_mv * vec4(a_pos, 1.0)).xyz;
    v_normal = mat3(u_mv) * a_normal;
    v_colour = a_colour;
}
