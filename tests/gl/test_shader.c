/* SPDX-License-Identifier: MIT */
/* test_shader.c: a deliberately broken shader gives an error naming its file
 * and stage with the compiler's log; a link error names the program. */
#include <GL/gl.h>
#include <GL/glext.h>
#include <string.h>

#include "gltest.h"

static const char good_vs[] = "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n";
static const char bad_fs[] = "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0) + undefined_thing; }\n";
static const char bad_vs[] = "#version 330 core\nvoid main() { gl_Position = vec3(0.0) }\n";
static const char vec3_vs[] = "#version 330 core\nout vec3 x;\n"
                              "void main() { x = vec3(0.0); gl_Position = vec4(0.0); }\n";
static const char needs_fs[] = "#version 330 core\nin vec4 x;\nout vec4 c;\nvoid main() { c = x; }\n";

int main(void)
{
    hy_gl *g = gl_or_skip(64, 64);
    hy_error err;
    unsigned prog = 0;
    hy_gl_stage s1[2] = {{"ok.vert.glsl", GL_VERTEX_SHADER, good_vs, NULL},
                            {"broken.frag.glsl", GL_FRAGMENT_SHADER, bad_fs, NULL}};
    int st = hy_gl_program(s1, 2, &prog, &err);
    printf("fragment: %s\n", err.msg);
    CHECK(st == HY_ENUM, "broken fragment shader accepted (%d)", st);
    CHECK(strstr(err.msg, "broken.frag.glsl") && strstr(err.msg, "fragment shader"), "message lacks file/stage");
    CHECK(strstr(err.msg, "undefined_thing") != NULL, "message lacks the compiler log");

    hy_gl_stage s2[1] = {{"broken.vert.glsl", GL_VERTEX_SHADER, bad_vs, NULL}};
    st = hy_gl_program(s2, 1, &prog, &err);
    printf("vertex: %s\n", err.msg);
    CHECK(st == HY_ENUM && strstr(err.msg, "broken.vert.glsl") && strstr(err.msg, "vertex shader"),
          "broken vertex shader: %s", err.msg);

    hy_gl_stage s3[2] = {{"vec3.vert.glsl", GL_VERTEX_SHADER, vec3_vs, NULL},
                            {"needs.frag.glsl", GL_FRAGMENT_SHADER, needs_fs, NULL}};
    st = hy_gl_program(s3, 2, &prog, &err);
    printf("link: %s\n", st ? err.msg : "(linked)");
    CHECK(st == HY_ENUM && strstr(err.msg, "link") && strstr(err.msg, "vec3.vert.glsl"), "link error: %s", err.msg);

    hy_gl_stage s4[2] = {{"ok.vert.glsl", GL_VERTEX_SHADER, good_vs, NULL},
                         {"ok.frag.glsl", GL_FRAGMENT_SHADER, "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n",
                          NULL}};
    CHECK(hy_gl_program(s4, 2, &prog, &err) == 0 && prog != 0, "a good program failed: %s", err.msg);

    /* defines go after the #version line (comments may come before it): the
     * shader compiles only with them, and a failure still names the file */
    const char *needs_define = "// a comment first\n#version 330 core\nout vec4 c;\nvoid main() { c = vec4(HY_LEVEL); }\n";
    hy_gl_stage s5[2] = {{"ok.vert.glsl", GL_VERTEX_SHADER, good_vs, NULL},
                         {"define.frag.glsl", GL_FRAGMENT_SHADER, needs_define, "#define HY_LEVEL 0.5\n"}};
    CHECK(hy_gl_program(s5, 2, &prog, &err) == 0, "shader with its define failed: %s", err.msg);
    s5[1].defines = NULL;
    st = hy_gl_program(s5, 2, &prog, &err);
    CHECK(st == HY_ENUM && strstr(err.msg, "define.frag.glsl") && strstr(err.msg, "HY_LEVEL"),
          "shader without its define: %d %s", st, st ? err.msg : "");
    hy_gl_free(g);
    return hy_test_finish("shader");
}
