/* SPDX-License-Identifier: MIT */
/* hy_formats.h: the figure file formats hystviz writes, one table.
 *
 * HY_FIGURE_FORMATS(X) calls X(ID, "ext", "mime") once per format, in the
 * order of the HY_FORMAT_ID values (hy_plot.h); mime is the Content-Type serve
 * answers it with (serve_render.c).  That enum, the schema's [output]
 * formats list, --format parsing and file names (scene_draw.c), sweep's
 * --formats, serve's fmt, the renderer's extension lookup and the output
 * writer's old temporary names and serve's Content-Type are generated from
 * it (the page's download list, src/serve/page, is still its own), so a new
 * format is one line here (and its writer in hy_output.c):
 *
 *     static const char *const ext[] = {HY_FIGURE_FORMATS(HY_FORMAT_EXT) NULL};
 *     printf("formats: %s\n", HY_FORMAT_NAMES);     ("svg, pdf, png")
 */
#ifndef HY_FORMATS_H
#define HY_FORMATS_H

#define HY_FIGURE_FORMATS(X)            \
    X(SVG, "svg", "image/svg+xml")      \
    X(PDF, "pdf", "application/pdf")    \
    X(PNG, "png", "image/png")

/* An X for HY_FIGURE_FORMATS: the extension, then a comma. */
#define HY_FORMAT_EXT(id, ext, mime) ext,
/* An X for HY_FIGURE_FORMATS: the MIME type, then a comma. */
#define HY_FORMAT_MIME(id, ext, mime) mime,

/* The extensions as one text, "svg, pdf, png", for messages. */
#define HY__FORMAT_LIST(id, ext, mime) ", " ext
#define HY_FORMAT_NAMES (&(HY_FIGURE_FORMATS(HY__FORMAT_LIST))[2]) /* past the first ", " */

#endif
