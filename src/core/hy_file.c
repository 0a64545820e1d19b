/* SPDX-License-Identifier: MIT */
/* hy_file.c: whole-file reads with a type check and a size cap (O_NONBLOCK open,
 * fstat on the descriptor, real path from /proc/self/fd), and message excerpts. */
#include "hy_file.h"

#include "hy_config.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *kind_of(mode_t m)
{
    if (S_ISDIR(m))
        return "a directory";
    if (S_ISFIFO(m))
        return "a FIFO";
    if (S_ISCHR(m))
        return "a character device";
    if (S_ISBLK(m))
        return "a block device";
    if (S_ISSOCK(m))
        return "a socket";
    return "not a regular file";
}

/* The real path of the open descriptor fd (Linux /proc), or NULL. */
static char *fd_path(int fd, const char *path)
{
    char link[64], buf[PATH_MAX];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    ssize_t n = readlink(link, buf, sizeof buf - 1);
    if (n > 0 && buf[0] == '/') {
        buf[n] = '\0';
        return strdup(buf);
    }
    return realpath(path, NULL);
}

static int fail(char *why, size_t whysz, int code, const char *fmt, const char *a)
{
    if (why && whysz)
        snprintf(why, whysz, fmt, a);
    return code;
}

/* Reads up to max + 1 bytes of fd; 0 or an errno code. */
static int read_all(int fd, size_t max, char **buf, size_t *len)
{
    size_t cap = 4096, n = 0;
    char *b = malloc(cap + 1);
    if (!b)
        return ENOMEM;
    for (;;) {
        if (n == cap) {
            if (cap > max)
                break;
            size_t nc = cap * 2 > max + 1 ? max + 1 : cap * 2;
            char *nb = realloc(b, nc + 1);
            if (!nb) {
                free(b);
                return ENOMEM;
            }
            b = nb;
            cap = nc;
        }
        ssize_t r = read(fd, b + n, cap - n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0) {
            int e = errno;
            free(b);
            return e;
        }
        if (r == 0)
            break;
        n += (size_t)r;
    }
    b[n] = '\0';
    *buf = b;
    *len = n;
    return 0;
}

int hy_file_read(const char *path, size_t max, char **buf, size_t *len, char **real, char *why,
                 size_t whysz)
{
    if (buf)
        *buf = NULL;
    if (len)
        *len = 0;
    if (real)
        *real = NULL;
    if (!path || !buf || !len)
        return fail(why, whysz, EINVAL, "%s must not be NULL", !path ? "path" : !buf ? "buf" : "len");
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) {
        int e = errno;
        return fail(why, whysz, e, "%s", strerror(e));
    }
    struct stat st;
    if (fstat(fd, &st)) {
        int e = errno;
        close(fd);
        return fail(why, whysz, e, "cannot stat: %s", strerror(e));
    }
    if (!S_ISREG(st.st_mode)) {
        close(fd);
        return fail(why, whysz, S_ISDIR(st.st_mode) ? EISDIR : EINVAL, "is %s, not a regular file",
                    kind_of(st.st_mode));
    }
    char lim[64];
    snprintf(lim, sizeof lim, "%zu", max);
    if ((unsigned long long)st.st_size > (unsigned long long)max) {
        close(fd);
        return fail(why, whysz, EFBIG, "is larger than the %s bytes allowed", lim);
    }
    /* back to blocking reads: a regular file never blocks, O_NONBLOCK only kept open() from hanging */
    int fl = fcntl(fd, F_GETFL);
    if (fl >= 0)
        fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
    int e = read_all(fd, max, buf, len);
    if (!e && *len > max) {
        free(*buf);
        *buf = NULL;
        e = EFBIG;
        close(fd);
        return fail(why, whysz, e, "is larger than the %s bytes allowed", lim);
    }
    if (e) {
        close(fd);
        return fail(why, whysz, e, "read error: %s", strerror(e));
    }
    if (real && !(*real = fd_path(fd, path))) {
        free(*buf);
        *buf = NULL;
        close(fd);
        return fail(why, whysz, ENOMEM, "%s", "cannot resolve its real path");
    }
    close(fd);
    return 0;
}

const char *hy_file_shown(const char *p, size_t n, size_t max, char *buf, size_t size)
{
    size_t o = 0, i = 0;
    if (!buf)
        return NULL;
    if (!size)
        return buf;
    if (!p)
        n = 0;
    buf[0] = '\0';
    for (; i < n && i < max; i++) {
        unsigned char c = (unsigned char)p[i];
        int w = isprint(c) ? snprintf(buf + o, size - o, "%c", c) : snprintf(buf + o, size - o, "\\x%02x", c);
        if (w < 0 || (size_t)w >= size - o)
            break;
        o += (size_t)w;
    }
    if (i < n && o + 4 <= size)
        snprintf(buf + o, size - o, "...");
    return buf;
}

const char *hy_file_excerpt(const char *p, size_t n, char *buf, size_t size)
{
    size_t m = 0;
    while (p && m < n && p[m] != '\n' && p[m] != '\r')
        m++;
    return hy_file_shown(p, m, 20, buf, size);
}

/* The running program's directory into dir (NUL-terminated); -1 if unknown. */
static int exe_dir(char *dir, size_t size)
{
    ssize_t n = readlink("/proc/self/exe", dir, size - 1);
    if (n <= 0 || (size_t)n >= size - 1)
        return -1;
    dir[n] = '\0';
    char *slash = strrchr(dir, '/');
    if (!slash)
        return -1;
    *slash = '\0';
    return 0;
}

static int exists(const char *path, int dir)
{
    struct stat st;
    return stat(path, &st) == 0 && (dir ? S_ISDIR(st.st_mode) : S_ISREG(st.st_mode));
}

/* The source tree of a program run from its build tree, into root: the
 * build writes it into HY_SOURCE_ROOT_FILE at the top of the build directory,
 * found from the program's directory dir upwards (at most 4 levels: build/,
 * build/src/app/, build/tests/cli/decoyprefix/); -1 for an installed program
 * (hy_file_installed uses only whether there is one). */
static int build_source_root(const char *dir, char *root, size_t size)
{
    char d[4096], path[4200];
    snprintf(d, sizeof d, "%s", dir);
    for (int up = 0; up < 4 && d[0]; up++) {
        if ((size_t)snprintf(path, sizeof path, "%s/" HY_SOURCE_ROOT_FILE, d) < sizeof path) {
            FILE *f = fopen(path, "r");
            if (f) {
                int ok = fgets(root, (int)size, f) != NULL;
                fclose(f);
                root[strcspn(root, "\n")] = '\0';
                return ok && root[0] == '/' ? 0 : -1;
            }
        }
        char *slash = strrchr(d, '/');
        if (!slash)
            break;
        *slash = '\0';
    }
    return -1;
}

/* Facts of the process, looked up once: the running program's directory
 * and whether it runs from its build tree.  hy_file_installed runs for every
 * scene read (hy_steady_loop's every call): a readlink and up to four opens
 * of HY_SOURCE_ROOT_FILE each time were a tenth of a 200-point call. */
static struct {
    int have;     /* self known */
    int in_build; /* a program in its build tree */
    char self[4096];
} exe_facts;
static pthread_once_t exe_once = PTHREAD_ONCE_INIT;

static void exe_facts_find(void)
{
    char root[4096];
    exe_facts.have = exe_dir(exe_facts.self, sizeof exe_facts.self) == 0;
    exe_facts.in_build = exe_facts.have && !build_source_root(exe_facts.self, root, sizeof root);
}

int hy_file_installed(int what, const char *sub, char *buf, size_t size)
{
    char self[4096];
    const char *rel = what == HY_INSTALLED_LIBEXEC ? HY_LIBEXECDIR_REL : HY_DATADIR_REL "/hystviz";
    const char *configured = what == HY_INSTALLED_LIBEXEC ? HY_LIBEXECDIR : HY_DATA_DIR;
    if (!buf && size)
        return -1;
    if (size)
        buf[0] = '\0';
    if (!sub || !size)
        return -1;
    pthread_once(&exe_once, exe_facts_find);
    int have = exe_facts.have;
    memcpy(self, exe_facts.self, sizeof self);
    /* the build tree: the helper program next to the running one */
    if (have && what == HY_INSTALLED_LIBEXEC && (size_t)snprintf(buf, size, "%s/%s", self, sub) < size &&
        exists(buf, 0))
        return 0;
    /* a program in its build tree never uses an install's files: it behaves
       as where nothing is installed (the tests of a build, or of an unpacked
       tarball, run the build's programs even where another hystviz is
       installed in the configured prefix: tests/cli/test_decoy.sh) */
    if (exe_facts.in_build) {
        if (size)
            buf[0] = '\0';
        return -1;
    }
    /* an install, wherever it now is: PREFIX/BINDIR/hystviz */
    size_t nb = strlen(HY_BINDIR_REL), ns = have ? strlen(self) : 0;
    if (have && ns > nb && self[ns - nb - 1] == '/' && !strcmp(self + ns - nb, HY_BINDIR_REL)) {
        self[ns - nb - 1] = '\0';
        if ((size_t)snprintf(buf, size, "%s/%s/%s", self, rel, sub) < size &&
            exists(buf, what == HY_INSTALLED_DATA))
            return 0;
    }
    if ((size_t)snprintf(buf, size, "%s/%s", configured, sub) < size && exists(buf, what == HY_INSTALLED_DATA))
        return 0;
    if (size)
        buf[0] = '\0';
    return -1;
}
