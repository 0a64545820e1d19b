/* SPDX-License-Identifier: MIT */
/* cmd_animate.h: `hystviz animate NAME [options]` and `hystviz animate --list`:
 * renders a built-in animation (anim_scenes.h) to PNG frames with the GL
 * engine (hy_anim.h).  argv[0] is "animate".  Returns 0 on success, 2 for a
 * usage error or a bad GL backend/device choice, 1 for a failed run, 3 when
 * GL or ffmpeg is unavailable (also when hystviz was built without OSMesa and
 * EGL: a message says so).  --gl B / $HYSTVIZ_GL pick the backend (hy_gl.h);
 * --gl-info describes it.
 *
 *     return hy_cmd_animate(argc - 1, argv + 1);    // from main()
 */
#ifndef HY_CMD_ANIMATE_H
#define HY_CMD_ANIMATE_H

/* Runs the animate command; messages go to stderr, the list and help to stdout. */
int hy_cmd_animate(int argc, char **argv);

#endif
