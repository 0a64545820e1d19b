/* SPDX-License-Identifier: MIT */
/* anim_assemble.c: frame ranges of a split animation and their assembly into
 * one video by ffmpeg's image2 demuxer (run without a shell: no quoting). */
#include "anim_assemble.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "hy_out.h"

void hy_anim_shard_range(long nframes, long k, long n, long *first, long *last)
{
    *first = (long)((long long)nframes * k / n);
    *last = (long)((long long)nframes * (k + 1) / n);
}

/* Appends the missing frames of [0, n) to msg as "A:B" ranges (at most 8);
 * returns how many frames are missing. */
static long missing_frames(const char *dir, long n, char *msg, size_t size)
{
    long missing = 0, ranges = 0, start = -1;
    size_t len = strlen(msg);
    for (long i = 0; i <= n; i++) {
        int have = 1;
        if (i < n) {
            char path[4400];
            struct stat st;
            snprintf(path, sizeof path, "%s/frame_%05ld.png", dir, i);
            have = !stat(path, &st) && S_ISREG(st.st_mode) && st.st_size > 0;
            missing += !have;
        }
        if (!have && start < 0)
            start = i;
        if (have && start >= 0) {
            if (ranges++ < 8 && len < size)
                len += (size_t)snprintf(msg + len, size - len, " %ld:%ld", start, i);
            start = -1;
        }
    }
    if (ranges > 8 && len < size)
        snprintf(msg + len, size - len, " ...");
    return missing;
}

/* Runs argv (argv[0] on PATH) through hy_out_spawn (a signal that ends this
 * process stops it first); 0 when it exits with status 0. */
static int run_wait(char *const argv[])
{
    pid_t pid;
    if (hy_out_spawn(argv, NULL, &pid))
        return -1;
    int status = hy_out_wait(pid);
    return status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : -1;
}

int hy_anim_assemble(const hy_anim_params *p, const char *fmt, hy_error *err)
{
    if (strcmp(fmt, "mp4") && strcmp(fmt, "webm") && strcmp(fmt, "gif"))
        return hy_error_set(err, HY_EINVAL, "--assemble: unknown video format '%s' (mp4, webm or gif)", fmt);
    long n = hy_anim_nframes(p);
    char dir[4200], pattern[4300], path[4300];
    if (snprintf(dir, sizeof dir, "%s/%s", p->outdir, p->name) >= (int)sizeof dir ||
        snprintf(path, sizeof path, "%s/%s.%s", p->outdir, p->name, fmt) >= (int)sizeof path)
        return hy_error_set(err, HY_EINVAL, "output directory name is too long");
    snprintf(pattern, sizeof pattern, "%s/frame_%%05d.png", dir);
    char msg[400] = "";
    long missing = missing_frames(dir, n, msg, sizeof msg);
    if (missing)
        return hy_error_set(err, HY_EINVAL, "--assemble: %ld of the %ld frames of %s are not in %s/ (render them with "
                            "--frames A:B, same options):%s", missing, n, p->name, dir, msg);
    if (!hy_anim_on_path("ffmpeg"))
        return hy_error_set(err, HY_EUNSUP, "--assemble needs ffmpeg, which is not on PATH (Debian: apt-get install "
                            "ffmpeg)");
    hy_out o;
    int st = hy_out_open(&o, path, 0, err); /* an empty temporary that ffmpeg fills (-y), then renamed */
    if (!st)
        st = hy_out_finish(&o, err);
    if (st)
        return st;
    char fps[40], count[32];
    snprintf(fps, sizeof fps, "%.17g", p->fps);
    snprintf(count, sizeof count, "%ld", n);
    char *argv[32];
    int a = 0;
    char *fixed[] = {"ffmpeg", "-loglevel", "error", "-y", "-framerate", fps, "-start_number", "0", "-i", pattern,
                     "-frames:v", count};
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++)
        argv[a++] = fixed[i];
    if (strcmp(fmt, "gif")) { /* as the piped encoder: hy_anim.c open_video */
        argv[a++] = "-c:v";
        argv[a++] = !strcmp(fmt, "mp4") ? "libx264" : "libvpx-vp9";
        argv[a++] = "-pix_fmt";
        argv[a++] = "yuv420p";
    }
    char *bitexact[] = {"-fflags", "+bitexact", "-flags:v", "+bitexact"}; /* as hy_anim.c open_video */
    for (size_t i = 0; i < sizeof bitexact / sizeof bitexact[0]; i++)
        argv[a++] = bitexact[i];
    argv[a++] = "-f";
    argv[a++] = (char *)fmt;
    argv[a++] = (char *)hy_out_tmp_path(&o);
    argv[a] = NULL;
    if (run_wait(argv)) {
        hy_out_abort(&o);
        return hy_error_set(err, HY_EIO, "ffmpeg failed to encode '%s' from %s (see its messages above)", path, pattern);
    }
    return hy_out_publish(&o, err);
}
