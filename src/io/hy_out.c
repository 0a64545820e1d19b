/* hy_out.c: the one output writer: mkstemp + flock + rename for files,
 * direct writes for FIFOs and character devices, "-" for standard output,
 * and the sweep of temporaries left by killed writers (hy_out.h). */
#include "hy_out.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#define TMP_TAG ".hystviz-tmp."

static mode_t file_mode;
static pthread_once_t mode_once = PTHREAD_ONCE_INIT;

/* The process umask, read without changing it where /proc says it (umask()
 * would set it for every thread for a moment). */
static void mode_init(void)
{
    mode_t mask = 022;
    int found = 0;
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    while (f && !found && fgets(line, sizeof line, f)) {
        unsigned m;
        if (sscanf(line, "Umask: %o", &m) == 1)
            mask = (mode_t)m, found = 1;
    }
    if (f)
        fclose(f);
    if (!found) {
        mask = umask(022);
        umask(mask);
    }
    file_mode = 0666 & ~mask;
}

static char *dupstr(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    return d ? memcpy(d, s, n) : NULL;
}

static int fail(hy_error *err, const char *path, int e)
{
    return hy_error_set(err, e == ENOMEM ? HY_ENOMEM : HY_EIO, "cannot write '%s': %s", path,
                        strerror(e ? e : EIO));
}

static int fail_msg(hy_error *err, const char *path, const char *why)
{
    return hy_error_set(err, HY_EIO, "cannot write '%s': %s", path, why);
}

/* The failure of o: its path, or "standard output". */
static int fail_out(hy_error *err, const hy_out *o, int e)
{
    if (o->direct != 1)
        return fail(err, o->path, e);
    return hy_error_set(err, e == ENOMEM ? HY_ENOMEM : HY_EIO, "cannot write standard output: %s", strerror(e ? e : EIO));
}

static void release(hy_out *o)
{
    if (o->fd >= 0)
        close(o->fd);
    free(o->path);
    free(o->final);
    free(o->tmp);
    free(o->membuf);
    o->fd = -1;
    o->path = o->final = o->tmp = o->membuf = NULL;
    o->fp = NULL;
    o->state = 3;
}

/* The temporary's name: DIR/.BASE.hystviz-tmp.XXXXXX next to final. */
static char *tmp_name(const char *final)
{
    const char *slash = strrchr(final, '/');
    size_t dlen = slash ? (size_t)(slash - final) + 1 : 0;
    const char *base = slash ? slash + 1 : final;
    size_t blen = strlen(base);
    if (blen > 200) /* the name only has to be recognisable: stay under NAME_MAX */
        blen = 200;
    char *t = malloc(dlen + blen + sizeof TMP_TAG + 8);
    if (t)
        sprintf(t, "%.*s.%.*s" TMP_TAG "XXXXXX", (int)dlen, final, (int)blen, base);
    return t;
}

/* Creates and locks the temporary.  A sweeper that took the lock of a file
 * just created (between mkstemp and flock) unlinks it: the writer sees its
 * name no longer leads to its file and makes another. */
static int open_tmp(hy_out *o, hy_error *err)
{
    for (int tries = 0; tries < 16; tries++) {
        free(o->tmp);
        if (!(o->tmp = tmp_name(o->final)))
            return fail(err, o->path, ENOMEM);
        int fd = mkstemp(o->tmp);
        if (fd < 0)
            return fail(err, o->path, errno);
        struct stat a, b;
        if (flock(fd, LOCK_EX) || fstat(fd, &a)) {
            int e = errno;
            close(fd);
            unlink(o->tmp);
            return fail(err, o->path, e);
        }
        if (lstat(o->tmp, &b) || a.st_ino != b.st_ino || a.st_dev != b.st_dev) {
            close(fd); /* swept away under us: another name */
            continue;
        }
        pthread_once(&mode_once, mode_init);
        fchmod(fd, file_mode);
        int keep = dup(fd); /* holds the lock once the stream is closed */
        FILE *fp = keep >= 0 ? fdopen(fd, "wb") : NULL;
        if (!fp) {
            int e = errno;
            if (keep >= 0)
                close(keep);
            close(fd);
            unlink(o->tmp);
            return fail(err, o->path, e);
        }
        o->fd = keep;
        o->fp = fp;
        return HY_OK;
    }
    return fail_msg(err, o->path, "its temporary files keep disappearing");
}

/* A FIFO or character device: opened as it is, never replaced. */
static int open_direct(hy_out *o, const struct stat *st, hy_error *err)
{
    int fd = open(o->final, O_WRONLY | O_NOCTTY | O_CLOEXEC);
    struct stat now;
    if (fd < 0)
        return fail(err, o->path, errno);
    if (fstat(fd, &now) || (now.st_mode & S_IFMT) != (st->st_mode & S_IFMT) || now.st_rdev != st->st_rdev) {
        close(fd);
        return fail_msg(err, o->path, "it changed while it was opened");
    }
    o->fd = fd;
    o->direct = 2;
    if (o->hold)
        return HY_OK; /* a memory stream until publish */
    int d = dup(fd);  /* the stream closes its own descriptor; publish closes fd */
    if (d < 0 || !(o->fp = fdopen(d, "wb"))) {
        int e = errno;
        if (d >= 0)
            close(d);
        return fail(err, o->path, e);
    }
    return HY_OK;
}

/* Decides what path is (hy_out.h) and sets o->final; 1 if it is a direct target. */
static int classify(hy_out *o, struct stat *st, hy_error *err)
{
    if (lstat(o->path, st)) {
        if (errno != ENOENT)
            return -fail(err, o->path, errno);
        return (o->final = dupstr(o->path)) ? 0 : -fail(err, o->path, ENOMEM);
    }
    if (S_ISLNK(st->st_mode)) {
        char *r = realpath(o->path, NULL);
        if (!r)
            return -(errno == ENOENT ? fail_msg(err, o->path, "it is a symbolic link to a missing file")
                                     : fail(err, o->path, errno));
        o->final = r;
        if (stat(r, st))
            return -fail(err, o->path, errno);
    } else if (!(o->final = dupstr(o->path)))
        return -fail(err, o->path, ENOMEM);
    if (S_ISREG(st->st_mode))
        return 0;
    if (S_ISFIFO(st->st_mode) || S_ISCHR(st->st_mode))
        return 1;
    return -fail_msg(err, o->path, S_ISDIR(st->st_mode) ? "it is a directory"
                                   : S_ISBLK(st->st_mode) ? "it is a block device"
                                                          : "it is not a regular file, FIFO or character device");
}

int hy_out_open(hy_out *o, const char *path, int flags, hy_error *err)
{
    memset(o, 0, sizeof *o);
    o->fd = -1;
    o->hold = (flags & HY_OUT_HOLD) != 0;
    if (!path || !*path)
        return hy_error_set(err, HY_EINVAL, "cannot write a file without a name");
    int rc = HY_OK;
    if (!(o->path = dupstr(path)))
        rc = fail(err, path, ENOMEM);
    else if (!strcmp(path, "-")) {
        o->direct = 1;
        o->fp = stdout;
    } else {
        struct stat st;
        int kind = classify(o, &st, err);
        rc = kind < 0 ? -kind : kind ? open_direct(o, &st, err) : open_tmp(o, err);
    }
    if (!rc && o->hold && o->direct && !(o->fp = open_memstream(&o->membuf, &o->memlen)))
        rc = fail(err, path, errno);
    if (rc) {
        release(o);
        return rc;
    }
    o->state = 1;
    return HY_OK;
}

FILE *hy_out_file(hy_out *o) { return o->fp; }

const char *hy_out_tmp_path(const hy_out *o) { return o->tmp ? o->tmp : o->final; }

void hy_out_abort(hy_out *o)
{
    if (o->state != 1 && o->state != 2)
        return;
    if (o->fp && o->fp != stdout)
        fclose(o->fp);
    if (o->tmp)
        unlink(o->tmp);
    release(o);
}

int hy_out_finish(hy_out *o, hy_error *err)
{
    if (o->state != 1)
        return hy_error_set(err, HY_EINVAL, "hy_out_finish: output not open");
    /* fflush first: after a failed write it tries the buffered bytes again,
     * and errno then says why (ENOSPC, EFBIG) where ferror alone cannot */
    int e = fflush(o->fp) ? errno : 0;
    if (!e && ferror(o->fp))
        e = EIO;
    if (o->fp != stdout && fclose(o->fp) && !e)
        e = errno;
    o->fp = NULL;
    if (e) {
        int code = fail_out(err, o, e);
        if (o->tmp)
            unlink(o->tmp);
        release(o);
        return code;
    }
    o->state = 2;
    return HY_OK;
}

/* Writes all n bytes to fd (retrying short writes); 0 or errno. */
static int write_all(int fd, const char *p, size_t n)
{
    while (n) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return w < 0 ? errno : EIO;
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

int hy_out_publish(hy_out *o, hy_error *err)
{
    if (o->state != 2)
        return hy_error_set(err, HY_EINVAL, "hy_out_publish: output not finished");
    int e = 0;
    if (o->tmp) {
        if (rename(o->tmp, o->final)) {
            e = errno;
            unlink(o->tmp);
        }
    } else if (o->hold && o->direct == 1) {
        if (fwrite(o->membuf, 1, o->memlen, stdout) != o->memlen || fflush(stdout))
            e = errno ? errno : EIO;
    } else if (o->hold)
        e = write_all(o->fd, o->membuf, o->memlen);
    if (o->direct == 2) {
        if (close(o->fd) && !e)
            e = errno;
        o->fd = -1;
    }
    int code = e ? fail_out(err, o, e) : HY_OK;
    release(o);
    return code;
}

int hy_out_commit(hy_out *o, hy_error *err)
{
    int rc = hy_out_finish(o, err);
    return rc ? rc : hy_out_publish(o, err);
}

int hy_out_is_tmp_name(const char *name)
{
    size_t n = strlen(name), t = sizeof TMP_TAG - 1;
    return name[0] == '.' && n > t + 7 && !memcmp(name + n - 6 - t, TMP_TAG, t);
}

/* "NAME.EXT.tmp.XXXXXX" of hystviz versions before hy_out. */
static int is_legacy_tmp(const char *name)
{
    static const char *const ext[] = {".svg", ".pdf", ".png", ".csv", ".html", ".manifest"};
    size_t n = strlen(name);
    if (n < 11 || memcmp(name + n - 11, ".tmp.", 5))
        return 0;
    for (size_t i = 0; i < sizeof ext / sizeof ext[0]; i++) {
        size_t k = strlen(ext[i]);
        if (n - 11 >= k && !memcmp(name + n - 11 - k, ext[i], k))
            return 1;
    }
    return 0;
}

int hy_out_sweep(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int dfd = dirfd(d), removed = 0;
    for (struct dirent *de; (de = readdir(d));) {
        if (!hy_out_is_tmp_name(de->d_name) && !is_legacy_tmp(de->d_name))
            continue;
        int fd = openat(dfd, de->d_name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
        struct stat a, b;
        if (fd < 0)
            continue;
        /* free lock: its writer is gone; same inode: still the file we locked */
        if (!fstat(fd, &a) && S_ISREG(a.st_mode) && !flock(fd, LOCK_EX | LOCK_NB) &&
            !fstatat(dfd, de->d_name, &b, AT_SYMLINK_NOFOLLOW) && a.st_ino == b.st_ino && a.st_dev == b.st_dev &&
            !unlinkat(dfd, de->d_name, 0))
            removed++;
        close(fd);
    }
    closedir(d);
    return removed;
}
