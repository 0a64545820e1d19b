// blit.frag: copies the resolved multisampled 3-D layer (premultiplied
// alpha, transparent where nothing was drawn) over the frame, pixel for pixel.
#version 330 core
uniform sampler2D u_tex;
out vec4 o_colour;

void main()
{
    o_colour = texelFetch(u_tex, ivec2(gl_FragCoord.xy), 0);
}
