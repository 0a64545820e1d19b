/* SPDX-License-Identifier: MIT */
/* hy_out.c: the one output writer: a temporary (O_EXCL) + flock + renameat in
 * the target's open directory for files, direct writes for FIFOs and character devices, "-" for standard output,
 * and the sweep of temporaries left by killed writers (hy_out.h). */
#define _GNU_SOURCE /* O_PATH, pipe2 */
#include "hy_out.h"
#include "hy_formats.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

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

/* What hy_out_end removes: every open temporary (the hy_out's own tmp
 * string and its directory's descriptor, registered while reg_mu is held
 * from the file's creation on) and the pids of the programs hy_out_spawn
 * started.  hy_out_end keeps reg_mu locked. */
typedef struct reg_tmp_entry {
    const char *tmp;
    int dfd;
} reg_tmp_entry;
static pthread_mutex_t reg_mu = PTHREAD_MUTEX_INITIALIZER;
static reg_tmp_entry *reg_tmp;
static pid_t *reg_pid;
static size_t reg_ntmp, reg_cap_tmp, reg_npid, reg_cap_pid;

/* Appends v to a registry array (reg_mu held); 0 or ENOMEM. */
static int reg_add(void **arr, size_t *n, size_t *cap, size_t size, const void *v)
{
    if (*n == *cap) {
        size_t c = *cap ? 2 * *cap : 16;
        void *a = realloc(*arr, c * size);
        if (!a)
            return ENOMEM;
        *arr = a, *cap = c;
    }
    memcpy((char *)*arr + *n * size, v, size);
    (*n)++;
    return 0;
}

static void reg_drop_tmp(const char *tmp)
{
    pthread_mutex_lock(&reg_mu);
    for (size_t i = 0; i < reg_ntmp; i++)
        if (reg_tmp[i].tmp == tmp) {
            reg_tmp[i] = reg_tmp[--reg_ntmp];
            break;
        }
    pthread_mutex_unlock(&reg_mu);
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
    if (o->tmp)
        reg_drop_tmp(o->tmp);
    if (o->fd >= 0)
        close(o->fd);
    if (o->dfd >= 0)
        close(o->dfd);
    o->dfd = -1;
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

/* The last component of a path. */
static const char *base_of(const char *p)
{
    const char *slash = strrchr(p, '/');
    return slash ? slash + 1 : p;
}

/* Replaces the trailing "XXXXXX" of name with random letters and digits. */
static void random_suffix(char *name)
{
    static const char set[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    unsigned char r[6];
    if (getrandom(r, sizeof r, GRND_NONBLOCK) != (ssize_t)sizeof r) {
        struct timespec ts; /* no entropy yet: the clock and the pid, O_EXCL does the rest */
        clock_gettime(CLOCK_MONOTONIC, &ts);
        uint64_t x = (uint64_t)ts.tv_nsec * 2654435761u ^ (uint64_t)getpid() << 20 ^ (uint64_t)(uintptr_t)name;
        for (size_t i = 0; i < sizeof r; i++, x >>= 7)
            r[i] = (unsigned char)x;
    }
    char *x = name + strlen(name) - 6;
    for (size_t i = 0; i < sizeof r; i++)
        x[i] = set[r[i] % (sizeof set - 1)];
}

/* Creates and locks the temporary in o->dfd (the target's directory, held
 * open: a directory renamed or a link planted on the way after the checks
 * does not move where the file goes).  A sweeper that took the lock of a
 * file just created (between its creation and flock) unlinks it: the writer
 * sees its name no longer leads to its file and makes another. */
static int open_tmp(hy_out *o, hy_error *err)
{
    for (int tries = 0; tries < 16; tries++) {
        if (o->tmp)
            reg_drop_tmp(o->tmp);
        free(o->tmp);
        if (!(o->tmp = tmp_name(o->final)))
            return fail(err, o->path, ENOMEM);
        random_suffix(o->tmp);
        const char *tb = base_of(o->tmp);
        /* created and registered at once: hy_out_end sees every temporary */
        pthread_mutex_lock(&reg_mu);
        int fd = openat(o->dfd, tb, O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600), e = errno;
        if (fd >= 0 && (e = reg_add((void **)&reg_tmp, &reg_ntmp, &reg_cap_tmp, sizeof *reg_tmp,
                                    &(reg_tmp_entry){o->tmp, o->dfd}))) {
            close(fd);
            unlinkat(o->dfd, tb, 0);
            fd = -1;
        }
        pthread_mutex_unlock(&reg_mu);
        if (fd < 0 && e == EEXIST)
            continue;
        if (fd < 0)
            return fail(err, o->path, e);
        struct stat a, b;
        if (flock(fd, LOCK_EX) || fstat(fd, &a)) {
            int e = errno;
            close(fd);
            unlinkat(o->dfd, tb, 0);
            return fail(err, o->path, e);
        }
        if (fstatat(o->dfd, tb, &b, AT_SYMLINK_NOFOLLOW) || a.st_ino != b.st_ino || a.st_dev != b.st_dev) {
            close(fd); /* swept away under us: another name */
            continue;
        }
        pthread_once(&mode_once, mode_init);
        fchmod(fd, file_mode);
        int keep = fcntl(fd, F_DUPFD_CLOEXEC, 0); /* holds the lock once the stream is closed */
        FILE *fp = keep >= 0 ? fdopen(fd, "wb") : NULL;
        if (!fp) {
            int e = errno;
            if (keep >= 0)
                close(keep);
            close(fd);
            unlinkat(o->dfd, tb, 0);
            return fail(err, o->path, e);
        }
        o->fd = keep;
        o->fp = fp;
        return HY_OK;
    }
    return fail_msg(err, o->path, "its temporary files keep disappearing");
}

/* A FIFO or character device: opened as it is, never replaced (the user's
 * own path: as the shell opens it, /dev/stdout's link to a pipe included;
 * else in its checked directory, no link followed). */
static int open_direct(hy_out *o, const struct stat *st, hy_error *err)
{
    int fd = o->follow ? open(o->final, O_WRONLY | O_NOCTTY | O_CLOEXEC)
                       : openat(o->dfd, base_of(o->final), O_WRONLY | O_NOCTTY | O_CLOEXEC | O_NOFOLLOW);
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
        if (stat(o->path, st))
            return -(errno == ENOENT ? fail_msg(err, o->path, "it is a symbolic link to a missing file")
                                     : fail(err, o->path, errno));
        /* the user's link to a FIFO or device is opened as the shell does:
         * /dev/stdout leads to "pipe:[N]", which no path names */
        int direct = S_ISFIFO(st->st_mode) || S_ISCHR(st->st_mode);
        char *r = o->follow && direct ? dupstr(o->path) : realpath(o->path, NULL);
        if (!r)
            return -(errno == ENOENT ? fail_msg(err, o->path, "it is a symbolic link to a missing file")
                                     : fail(err, o->path, errno));
        o->final = r;
        if (!o->follow && stat(r, st))
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

/* A descriptor (O_PATH) of the directory that holds path's last component,
 * or -1 with errno. */
static int open_dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return open(".", O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (slash == path)
        return open("/", O_PATH | O_DIRECTORY | O_CLOEXEC);
    char *d = malloc((size_t)(slash - path) + 1);
    if (!d)
        return errno = ENOMEM, -1;
    memcpy(d, path, (size_t)(slash - path));
    d[slash - path] = '\0';
    int fd = open(d, O_PATH | O_DIRECTORY | O_CLOEXEC);
    int e = errno;
    free(d);
    errno = e;
    return fd;
}

/* 1 if directory dfd is root or lies below it (walking up through ".."
 * from the descriptor: what the directory is now, not what a path said),
 * 0 if not, -1 with errno. */
static int dir_below(int dfd, const struct stat *root)
{
    int cur = openat(dfd, ".", O_PATH | O_DIRECTORY | O_CLOEXEC), rc = -1;
    for (int depth = 0; cur >= 0 && depth < 4096; depth++) {
        struct stat a, b;
        if (fstat(cur, &a))
            break;
        if (a.st_dev == root->st_dev && a.st_ino == root->st_ino) {
            rc = 1;
            break;
        }
        int up = openat(cur, "..", O_PATH | O_DIRECTORY | O_CLOEXEC);
        if (up < 0 || fstat(up, &b)) {
            if (up >= 0)
                close(up);
            break;
        }
        close(cur);
        cur = up;
        if (a.st_dev == b.st_dev && a.st_ino == b.st_ino) { /* "/": its own parent */
            rc = 0;
            break;
        }
    }
    if (cur >= 0)
        close(cur);
    return rc;
}

/* Opens o->dfd, the directory o->final goes into; unless the path is the
 * user's own (HY_OUT_FOLLOW) it must be the directory of the path as given
 * or below it: a link planted at the name does not lead the file out. */
static int open_target_dir(hy_out *o, hy_error *err)
{
    if ((o->dfd = open_dir_of(o->final)) < 0)
        return fail(err, o->path, errno);
    if (o->follow || !strcmp(o->final, o->path))
        return HY_OK;
    struct stat root;
    int rfd = open_dir_of(o->path);
    int below = rfd >= 0 && !fstat(rfd, &root) ? dir_below(o->dfd, &root) : -1;
    int e = errno;
    if (rfd >= 0)
        close(rfd);
    if (below < 0)
        return fail(err, o->path, e);
    if (!below) {
        char dir[256];
        const char *slash = strrchr(o->path, '/');
        size_t n = slash ? (size_t)(slash - o->path) + (slash == o->path) : 1;
        snprintf(dir, sizeof dir, "%.*s", (int)(n < sizeof dir ? n : sizeof dir - 1), slash ? o->path : ".");
        return hy_error_set(err, HY_EINVAL,
                            "refusing to write '%s': it is a symbolic link to '%s', outside '%s'; a file whose "
                            "name comes from a scene or an output directory is written only below that directory "
                            "(docs/SCENES.md, \"Files a scene may read and write\")", o->path, o->final, dir);
    }
    return HY_OK;
}

static void sweep_own(const hy_out *o);

int hy_out_open(hy_out *o, const char *path, int flags, hy_error *err)
{
    memset(o, 0, sizeof *o);
    o->fd = -1;
    o->dfd = -1;
    o->hold = (flags & HY_OUT_HOLD) != 0;
    o->follow = (flags & HY_OUT_FOLLOW) != 0;
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
        rc = kind < 0 ? -kind : open_target_dir(o, err);
        if (!rc && !kind && o->follow)
            sweep_own(o); /* a directory of its own sweeps itself; the user's file is swept here */
        if (!rc)
            rc = kind ? open_direct(o, &st, err) : open_tmp(o, err);
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
        unlinkat(o->dfd, base_of(o->tmp), 0);
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
            unlinkat(o->dfd, base_of(o->tmp), 0);
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
        /* renameat replaces whatever the name is now, a link planted since
         * included, and never follows it */
        if (renameat(o->dfd, base_of(o->tmp), o->dfd, base_of(o->final))) {
            e = errno;
            unlinkat(o->dfd, base_of(o->tmp), 0);
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
#define DOT_EXT(id, e, mime) "." e,
    static const char *const ext[] = {HY_FIGURE_FORMATS(DOT_EXT) ".csv", ".html", ".manifest"};
#undef DOT_EXT
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

/* Removes the stale temporaries in the directory d reads (opened on dfd):
 * every one, or with base only those of that target name. */
static int sweep_dir(DIR *d, const char *base)
{
    int dfd = dirfd(d), removed = 0;
    size_t blen = base ? strlen(base) : 0, t = sizeof TMP_TAG - 1;
    if (blen > 200)
        blen = 200; /* as tmp_name cuts it */
    for (struct dirent *de; (de = readdir(d));) {
        if (base ? !(hy_out_is_tmp_name(de->d_name) && strlen(de->d_name) == 1 + blen + t + 6 &&
                     !memcmp(de->d_name + 1, base, blen) && !memcmp(de->d_name + 1 + blen, TMP_TAG, t))
                 : !hy_out_is_tmp_name(de->d_name) && !is_legacy_tmp(de->d_name))
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

int hy_out_sweep(const char *dir)
{
    DIR *d = opendir(dir);
    return d ? sweep_dir(d, NULL) : 0;
}

/* The stale temporaries of o's own target (a killed run of the same
 * command, e.g. `data -o FILE`), in its open directory. */
static void sweep_own(const hy_out *o)
{
    int fd = openat(o->dfd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    DIR *d = fd >= 0 ? fdopendir(fd) : NULL;
    if (d)
        sweep_dir(d, base_of(o->final));
    else if (fd >= 0)
        close(fd);
}

int hy_out_spawn(char *const argv[], int *in_fd, pid_t *pid)
{
    int p[2] = {-1, -1};
    if (in_fd && pipe2(p, O_CLOEXEC))
        return errno;
    posix_spawn_file_actions_t fa;
    posix_spawnattr_t at;
    sigset_t none, dfl;
    sigemptyset(&none);
    sigemptyset(&dfl);
    sigaddset(&dfl, SIGINT);
    sigaddset(&dfl, SIGTERM);
    sigaddset(&dfl, SIGPIPE);
    posix_spawn_file_actions_init(&fa);
    posix_spawnattr_init(&at);
    if (in_fd)
        posix_spawn_file_actions_adddup2(&fa, p[0], 0);
    else
        posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawnattr_setsigmask(&at, &none);
    posix_spawnattr_setsigdefault(&at, &dfl);
    posix_spawnattr_setflags(&at, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    pthread_mutex_lock(&reg_mu); /* started and registered at once */
    int e = posix_spawnp(pid, argv[0], &fa, &at, argv, environ);
    if (!e && (e = reg_add((void **)&reg_pid, &reg_npid, &reg_cap_pid, sizeof *reg_pid, pid))) {
        kill(*pid, SIGKILL);
        waitpid(*pid, NULL, 0);
    }
    pthread_mutex_unlock(&reg_mu);
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&at);
    if (in_fd) {
        close(p[0]);
        if (e)
            close(p[1]);
        else
            *in_fd = p[1];
    }
    return e;
}

int hy_out_wait(pid_t pid)
{
    /* waited for without reaping, dropped from the registry, then reaped: a
     * pid hy_out_end could kill is never one the system gave to another */
    siginfo_t si;
    while (waitid(P_PID, (id_t)pid, &si, WEXITED | WNOWAIT) < 0)
        if (errno != EINTR)
            return -1;
    pthread_mutex_lock(&reg_mu);
    for (size_t i = 0; i < reg_npid; i++)
        if (reg_pid[i] == pid) {
            reg_pid[i] = reg_pid[--reg_npid];
            break;
        }
    pthread_mutex_unlock(&reg_mu);
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -1;
    return status;
}

void hy_out_end(void)
{
    pthread_mutex_lock(&reg_mu); /* kept: no temporary or program starts after this */
    for (size_t i = 0; i < reg_npid; i++)
        kill(reg_pid[i], SIGKILL);
    siginfo_t si;
    for (size_t i = 0; i < reg_npid; i++) /* gone before their files: none writes one again */
        while (waitid(P_PID, (id_t)reg_pid[i], &si, WEXITED | WNOWAIT) < 0 && errno == EINTR)
            ;
    for (size_t i = 0; i < reg_ntmp; i++)
        unlinkat(reg_tmp[i].dfd, base_of(reg_tmp[i].tmp), 0);
}
