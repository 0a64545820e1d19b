/* SPDX-License-Identifier: MIT */
/* hy_quality.h: the animation quality presets, one table for the scene schema
 * ([animation] quality) and for `hystviz animate --quality`.
 *
 * HY_QUALITY_PRESETS(X) calls X(name, width, height, fps) once per preset:
 *
 *     #define NAME(n, w, h, fps) n,
 *     static const char *const names[] = {HY_QUALITY_PRESETS(NAME) NULL};
 */
#ifndef HY_QUALITY_H
#define HY_QUALITY_H

#ifdef __cplusplus
extern "C" {
#endif

#define HY_QUALITY_PRESETS(X)                                                    \
    X("480p15", 854, 480, 15)                                                    \
    X("480p30", 854, 480, 30)                                                    \
    X("720p30", 1280, 720, 30)                                                   \
    X("720p60", 1280, 720, 60)                                                   \
    X("1080p30", 1920, 1080, 30)                                                 \
    X("1080p60", 1920, 1080, 60)                                                 \
    X("1440p60", 2560, 1440, 60)                                                 \
    X("2160p60", 3840, 2160, 60)

#ifdef __cplusplus
}
#endif

#endif
