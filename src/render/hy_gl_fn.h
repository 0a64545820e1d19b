/* SPDX-License-Identifier: MIT */
/* hy_gl_fn.h (private to the GL backends): the OpenGL entry points that
 * hy_gl.c calls, looked up at run time from the backend that made the context
 * (OSMesaGetProcAddress, eglGetProcAddress) instead of being linked.  Linking
 * one library's gl* symbols would tie every context to it: libOSMesa's entry
 * points do not reach a vendor's EGL driver (NVIDIA's), and glvnd's libOpenGL
 * does not reach an OSMesa context.  A build with only one backend links no
 * GL library but that backend's (libOSMesa or libEGL).
 *
 * HY_GL_FUNCS(X) lists them without their "gl" prefix; hy_gl_fns holds one
 * pointer each, typed from the prototypes of GL/glext.h, so that hy_gl.c
 * writes gl->Clear(GL_COLOR_BUFFER_BIT) with the compiler checking the
 * arguments. */
#ifndef HY_GL_FN_H
#define HY_GL_FN_H

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#define HY_GL_FUNCS(X) \
    X(AttachShader) X(BindBuffer) X(BindFramebuffer) X(BindRenderbuffer) X(BindVertexArray) \
    X(BlendFuncSeparate) X(BlitFramebuffer) X(BufferData) X(CheckFramebufferStatus) X(Clear) X(ClearColor) \
    X(ClearDepth) X(CompileShader) X(CreateProgram) X(CreateShader) X(DeleteFramebuffers) X(DeleteProgram) \
    X(DeleteRenderbuffers) X(DeleteShader) X(DepthFunc) X(Disable) X(DrawArrays) X(DrawArraysInstanced) X(DrawElements) \
    X(Enable) X(EnableVertexAttribArray) X(Finish) X(FramebufferRenderbuffer) X(GenBuffers) X(GenFramebuffers) \
    X(GenRenderbuffers) X(GenVertexArrays) X(GetError) X(GetProgramInfoLog) X(GetProgramiv) \
    X(GetShaderInfoLog) X(GetShaderiv) X(GetString) X(GetUniformLocation) X(LinkProgram) X(PixelStorei) \
    X(ReadPixels) X(RenderbufferStorage) X(RenderbufferStorageMultisample) X(Scissor) X(ShaderSource) \
    X(Uniform1f) X(Uniform1fv) X(Uniform1i) X(Uniform2f) X(Uniform3f) X(Uniform4f) X(UniformMatrix4fv) X(UseProgram) \
    X(VertexAttribDivisor) X(VertexAttribPointer) X(Viewport)

#define HY_GL_FN_FIELD(name) __typeof__(gl##name) *name;
typedef struct hy_gl_fns {
    HY_GL_FUNCS(HY_GL_FN_FIELD)
} hy_gl_fns;
#undef HY_GL_FN_FIELD

/* An entry point by name ("glClear"), NULL when the library has none. */
typedef void (*hy_gl_proc)(void);
typedef hy_gl_proc (*hy_gl_lookup)(const char *name);

/* Fills f through lookup; NULL when all were found, else the first missing name. */
const char *hy_gl_fns_load(hy_gl_fns *f, hy_gl_lookup lookup);

#endif
